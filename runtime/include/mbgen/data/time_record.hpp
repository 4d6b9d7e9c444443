// A measured time record: sampled inputs and outputs on a uniform time grid.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "mbgen/data/data_settings.hpp"

namespace mbgen {

struct Signal {
  std::string name;       // a model input or output name (or, unchecked, any column name)
  Eigen::VectorXd values; // one value per sample
};

struct TimeRecord {
  std::string file;           // where it was read from, for messages ("-" for standard input)
  SetMap set;                 // `# set NAME=VALUE` lines
  HoldMode hold = HoldMode::ZeroOrder;
  Eigen::VectorXd t;          // seconds, strictly increasing, uniform within the reader's tolerance
  std::vector<Signal> signals;  // in file column order

  Eigen::Index samples() const { return t.size(); }
  // Sample interval (t_last - t_first) / (samples - 1); needs at least 2 samples.
  double dt() const;
  // The signal called `name`, or nullptr.
  const Signal* find(const std::string& name) const;
  // The signal called `name`; throws DataError naming the file and the signals it has.
  const Signal& at(const std::string& name) const;
};

// Throws DataError (naming the file and the missing names) unless every one of `inputs` is a signal of the
// record: a simulation needs all model inputs.
void require_inputs(const TimeRecord& record, const std::vector<std::string>& inputs);

// Largest deviation of a sample time from the uniform grid, as a fraction of the sample interval, that the
// readers accept (see docs/data.md).
constexpr double kTimeGridTolerance = 1e-2;

}  // namespace mbgen
