// Which of a model's parameters explain a change found in operation (docs/monitor.md, "Which parameters explain a
// change"): the model's modes paired with the tracked ones by MAC at the sensors, the relative sensitivities of
// their frequencies (thesis Eq. 4.12, S = (1/f) df/dp, times p: the relative change of f per relative change of
// p), and per parameter alone a weighted least-squares fit of the change's compensated relative shifts.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "mbgen/model.hpp"
#include "mbgen/monitoring/operational_monitor.hpp"

namespace mbgen {

struct OperationalModelModes {
  std::vector<std::string> parameters;  // the model's, in model order
  std::vector<int> model_mode;          // per tracked mode: the model's oscillating mode (by frequency), -1: none
  std::vector<double> mac, f_hz;        // per tracked mode: MAC with it at the sensors, its frequency
  Eigen::MatrixXd sensitivity;          // tracked modes x parameters: (p / f) df/dp (0 for an unpaired mode)
};

// `channels`: the data's response names, which must be outputs of the model (std::invalid_argument otherwise).
// A tracked mode is paired with the model mode of largest MAC of its shape with the model's C v at the channels,
// one to one, largest MAC first; with MAC below `min_mac` it stays unpaired.
OperationalModelModes operational_model_modes(const Model& model, const Eigen::VectorXd& values,
                                              const std::vector<std::string>& channels,
                                              const OperationalMonitorResult& monitored, double min_mac = 0.8);

struct ParameterExplanation {
  std::string name;
  double relative_change = 0;  // the fitted change of the parameter, as a fraction of its value
  double chi2 = 0;             // the fit's weighted residual (the shifts' sigmas as weights)
  bool consistent = false;     // chi2 within its 99 % quantile (dof: the compensated features - 1)
  bool plausible = false;      // |relative_change| <= 0.5
};

struct ChangeExplanation {
  int dof = 0;            // compensated features - 1: 0 means every sensitive parameter fits exactly
  double chi2_limit = 0;  // the 99 % quantile of chi2 with dof degrees of freedom (0 for dof 0)
  std::vector<ParameterExplanation> parameters;  // consistent and plausible first, then by chi2, then by |change|
  std::vector<std::string> named;                // those consistent and plausible, in that order
  std::string text;
};

ChangeExplanation explain_change(const OperationalModelModes& model, const OperationalMonitorResult& monitored,
                                 const OperationalChange& change);

}  // namespace mbgen
