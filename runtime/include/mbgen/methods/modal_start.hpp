// A start for a fit from the data's own modes (docs/estimation.md, "Start from the data's modes").
//
// A fit from priors a factor of a few off can end with every parameter at a bound: its output-error cost, from
// there, sees model peaks on the wrong side of the measured ones, and the multistart's random points, drawn around
// the same priors, share the problem. The data's modes say where the peaks are without any model:
//
//   ModalStart s = mbgen::start_from_modes(model, data, options);
//   if (!s.values.empty()) options.also_start_at = s.values;   // one more start of the global search
//
// 1. The reference modes: LSCF poles, automatic selection, LSFD residues (modal_identification.hpp) of the FRFs
//    (time records: of the H1 estimates the fit's search uses, spectral_companion.hpp), per configuration as the
//    modal method groups them (`# set` values).
// 2. The model's modes paired with them by MAC times the ratio of residue norms at every evaluation, so a model
//    whose frequencies are far off still pairs by shape; where the model has fewer modes than the data, the data's
//    weakest modes are left out.
// 3. One Levenberg-Marquardt solve of all mass/stiffness parameters (log scale, within bounds) on every mode's
//    frequency, shape and residue scale (the modal method's objectives), from the priors; then the damping
//    parameters by least squares on the modal damping ratios. Parameters acting on the input or output map, or on
//    damping and stiffness at once, stay at their priors.
//
// Neither signs nor a single calibration factor of a channel change a MAC or a residue norm, so the start is the
// same whether or not the measurement chain is right. The start is only a start: the fit's own cost decides.
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <map>
#include <string>
#include <vector>

namespace mbgen {

struct ModalStart {
  std::map<std::string, double> values;  // the placed parameters by name; empty when no start was placed
  std::vector<double> f_hz;              // the data's modes the start was placed on
  double cost_at_prior = 0, cost = 0;    // the modal objectives' sum of squares at the priors and at the start
  // One line: "5 modes (0.61-3.9 Hz): 10 mass/stiffness and 5 damping parameters placed, modal misfit 12.3 ->
  // 0.0021", or why no start was placed.
  std::string summary;
};

// Never throws for data it cannot use (no modes, a model with too few modes, ...): summary says why and values is
// empty. FitOptions: the estimated parameters and values (priors) as fit() takes them, and the local solver's
// stopping rules.
ModalStart start_from_modes(const Model& model, const std::vector<DataSet>& data, const FitOptions& options);

// Makes `values` the search's first chosen start (FitOptions::also_start_at), any chosen start already there moving
// to the front of further_starts_at, with at least two starts so the priors keep theirs. Nothing for empty values.
void start_first_at(const std::map<std::string, double>& values, FitOptions& options);

}  // namespace mbgen
