// MATLAB's `compare` fit percentage of an estimate on other data (mbgen/estimation/validation_fit.hpp).
#include "mbgen/estimation/validation_fit.hpp"

#include "mbgen/estimation/fit.hpp"

#include "output_error.hpp"

#include <cmath>
#include <limits>

namespace mbgen {

double compare_fit_percent(const Eigen::VectorXcd& measured, const Eigen::VectorXcd& model, bool subtract_mean) {
  const std::complex<double> baseline = subtract_mean ? measured.mean() : std::complex<double>(0);
  const double scale = (measured.array() - baseline).matrix().norm();
  if (!(scale > 0)) return std::numeric_limits<double>::quiet_NaN();
  return 100 * (1 - (measured - model).norm() / scale);
}

void check_validation_data(const Model& model, const std::vector<DataSet>& data) {
  // The fit's own problem checks the data's shape when it is built.
  const estimation::OutputErrorProblem problem(model, data, FrfWeighting{});
  (void)problem;
}

std::vector<ValidationScore> validation_scores(const Model& model, const std::vector<DataSet>& data,
                                               const Eigen::VectorXd& values) {
  const Prediction prediction = predict(model, data, values);
  std::vector<ValidationScore> out;
  for (std::size_t d = 0; d < data.size(); ++d) {
    ValidationScore score;
    score.file = data[d].file();
    score.frf = data[d].is_frf();
    for (std::size_t c = 0; c < prediction.channels[d].size(); ++c) {
      const std::string& name = prediction.channel_names[d][c];
      Eigen::VectorXcd measured;
      if (score.frf) {
        const FrfData& f = std::get<FrfData>(data[d].content);
        measured = f.channels[c].values;
      } else {
        measured = std::get<TimeRecord>(data[d].content).at(name).values.cast<std::complex<double>>();
      }
      score.channels.push_back({name, compare_fit_percent(measured, prediction.channels[d][c], !score.frf)});
    }
    out.push_back(std::move(score));
  }
  return out;
}

}  // namespace mbgen
