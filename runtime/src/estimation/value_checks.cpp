#include "value_checks.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mbgen/data/data_error.hpp"

namespace mbgen::estimation {

namespace {

std::string text_of(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Empty if `values` are admissible, else why not.
std::string problem_with(const Model& model, const Eigen::VectorXd& values) {
  const ModelInfo& info = model.info();
  for (std::size_t i = 0; i < info.parameters.size(); ++i) {
    const ParameterInfo& p = info.parameters[i];
    const double v = values[static_cast<Eigen::Index>(i)];
    if (!std::isfinite(v)) return "parameter " + p.name + " = " + text_of(v) + " is not finite";
    if (v < p.lower || v > p.upper)
      return "parameter " + p.name + " = " + text_of(v) + " lies outside its bounds [" + text_of(p.lower) + ", " +
             text_of(p.upper) + "]";
  }
  ModelMatrices m;
  model.evaluate(values, m);
  if (m.M.size() > 0 && Eigen::LLT<Eigen::MatrixXd>(m.M).info() != Eigen::Success)
    return "the mass matrix is not positive definite at these values (a mass or inertia is zero or negative)";
  return "";
}

}  // namespace

void check_parameter_values(const Model& model, const Eigen::VectorXd& values, const std::string& where) {
  if (const std::string problem = problem_with(model, values); !problem.empty())
    throw FitError("fit: " + where + ": " + problem);
}

void check_data_set_values(const Model& model, const Eigen::VectorXd& prior, const std::vector<DataSet>& data) {
  const ModelInfo& info = model.info();
  for (const DataSet& d : data) {
    if (d.set().empty()) continue;
    Eigen::VectorXd values = prior;
    int line = 0;
    for (const auto& [name, value] : d.set()) {
      const int idx = info.parameter_index(name);
      if (idx < 0)
        throw DataError(d.file(), value.line, 0, "`# set " + name + "`: the model has no free parameter " + name);
      values[idx] = value.value;
      line = std::max(line, value.line);
    }
    if (const std::string problem = problem_with(model, values); !problem.empty())
      throw DataError(d.file(), line, 0, "the values of its `# set` lines are not admissible: " + problem);
  }
}

void check_measured_signals(const Model& model, const std::vector<DataSet>& data) {
  const ModelInfo& info = model.info();
  const auto largest = [](const auto& v) { return v.size() == 0 ? 0.0 : double(v.cwiseAbs().maxCoeff()); };
  // A signal all of whose values lie below kMinSignalMagnitude (but not all zero) has squares below the smallest
  // normal double: its sum of squares underflows to zero and the fit's nrmse became NaN, with exit status 0 and an
  // estimate computed from noise weights that had underflowed too.
  const auto too_small = [](double peak) {
    return "its largest magnitude, " + text_of(peak) +
           ", is below 1e-150, where squares underflow a double; give the data in smaller units";
  };
  for (const DataSet& d : data) {
    if (d.is_frf()) {
      for (const FrfChannel& c : std::get<FrfData>(d.content).channels) {
        const std::string name = "FRF " + c.output + "/" + c.input;
        const double peak = largest(c.values);
        if (peak == 0) throw DataError(d.file(), 0, 0, name + " is zero at every frequency: there is nothing to fit");
        if (peak < kMinSignalMagnitude)
          throw DataError(d.file(), 0, 0, name + " is too small to fit: " + too_small(peak));
      }
      continue;
    }
    double input_peak = 0;
    bool any_input = false;
    for (const Signal& s : std::get<TimeRecord>(d.content).signals) {
      const double peak = largest(s.values);
      if (info.input_index(s.name) >= 0) {
        any_input = true;
        input_peak = std::max(input_peak, peak);
      }
      if (info.output_index(s.name) < 0) continue;
      if (peak == 0)
        throw DataError(d.file(), 0, 0, "output " + s.name + " is zero throughout the record: there is nothing to fit");
      if (peak < kMinSignalMagnitude)
        throw DataError(d.file(), 0, 0, "output " + s.name + " is too small to fit: " + too_small(peak));
    }
    if (!any_input) {  // it was called "every input is zero throughout the record", true but not the point
      std::string names;
      for (const std::string& n : info.inputs) names += (names.empty() ? "" : ", ") + n;
      throw DataError(d.file(), 0, 0,
                      "the record has no column of the model's inputs (" + names +
                          "): the model's response would be zero");
    }
    if (input_peak == 0)
      throw DataError(d.file(), 0, 0, "every input is zero throughout the record: the model's response would be zero");
    if (input_peak < kMinSignalMagnitude)
      throw DataError(d.file(), 0, 0, "every input is too small: " + too_small(input_peak));
  }
}

}  // namespace mbgen::estimation
