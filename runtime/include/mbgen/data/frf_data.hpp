// Measured frequency response functions: complex values of output per unit input at a list of frequencies.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "mbgen/data/data_settings.hpp"

namespace mbgen {

struct FrfChannel {
  std::string output;  // model output name (numerator)
  std::string input;   // model input name (denominator)
  Eigen::VectorXcd values;                  // one per frequency, units of output per unit of input
  std::optional<Eigen::VectorXd> coherence;  // 0..1, one per frequency, when measured
};

struct FrfData {
  std::string file;  // where it was read from, for messages
  SetMap set;        // `# set NAME=VALUE` lines
  Eigen::VectorXd f_hz;  // frequencies in Hz, non-negative, strictly increasing
  std::vector<FrfChannel> channels;  // in file column order
  // Read from UFF 58: the ordinate's specific data type (record 9) that all the FRF records declare (8 displacement,
  // 11 velocity, 12 acceleration, ...); 0 for CSV, or when the records differ. Kept with the data so that it does
  // not depend on the file's name or on reading it twice (standard input and pipes cannot be).
  int uff_ordinate_type = 0;

  // The channel OUTPUT/INPUT, or nullptr.
  const FrfChannel* find(const std::string& output, const std::string& input) const;
};

// The lines of `data` within [lo_hz, hi_hz] (a fit band: the band a model is meant to represent). Throws
// std::invalid_argument when no line is left.
FrfData within_band(const FrfData& data, double lo_hz, double hi_hz);

}  // namespace mbgen
