// Settings carried by a measured data file besides its signals: per-data-set parameter values
// (`# set NAME=VALUE`), the input hold mode (`# hold=none`), and the model's channel names used to check
// the file's columns.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mbgen {

// A parameter value given by `# set NAME=VALUE`: the decimal text exactly as written (for exact use by the
// compiler) and its double value.
struct SetValue {
  std::string text;
  double value = 0;
  int line = 0;  // of the `# set` line in its file (0: not from a file)
};
using SetMap = std::map<std::string, SetValue>;

// How inputs behave between samples of a time record (docs/interfaces.md, "Measured data").
enum class HoldMode {
  ZeroOrder,  // default: each input sample is held constant until the next one
  None,       // `# hold=none`: band-limited inputs sampled without hold
};

// The model's input and output names. Readers given these reject any other channel name.
struct ChannelNames {
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  bool is_input(const std::string& n) const;
  bool is_output(const std::string& n) const;
  // "inputs: a, b; outputs: c" for error messages.
  std::string describe() const;
};

}  // namespace mbgen
