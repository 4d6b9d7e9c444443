// New names for what the extension operators add, never clashing with any name the model already uses.
#pragma once

#include <set>
#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

class NameSet {
 public:
  // Every name of the model, whatever it names (parameter, frame, element, signal), and the reserved words.
  explicit NameSet(const ir::ModelIr& model);

  // `base` if unused, else `base_2`, `base_3`, ...; the name returned is taken from then on.
  std::string fresh(const std::string& base);

 private:
  std::set<std::string> used_;
};

}  // namespace mbgen::diagnosis
