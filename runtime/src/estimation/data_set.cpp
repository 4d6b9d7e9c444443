#include "mbgen/fit.hpp"

namespace mbgen {

const std::string& DataSet::file() const {
  return is_frf() ? std::get<FrfData>(content).file : std::get<TimeRecord>(content).file;
}
const SetMap& DataSet::set() const {
  return is_frf() ? std::get<FrfData>(content).set : std::get<TimeRecord>(content).set;
}

}  // namespace mbgen
