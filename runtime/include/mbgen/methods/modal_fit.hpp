// The "modal" method (Ellinger & Zaeh 2022, Sec. 2.3; docs/methods.md#modal): the parameters fitted to modes
// identified from measured FRFs instead of to the FRFs themselves.
//
//   FitResult r = mbgen::fit_modal(model, data, options);   // r.method == "modal"
//
// 1. Reference modes from the FRFs by experimental modal analysis (LSCF poles, automatic selection, refined poles,
//    LSFD residues: modal_identification.hpp), per configuration (the data sets sharing their `# set` values, which
//    hold in the model evaluated for them: Ellinger & Zaeh's machine positions), paired at every evaluation with the
//    model's modes in that configuration by MAC times the ratio of the residue norms.
// 2. Per mode the objectives: natural frequency difference (f - f_ref) / f_ref, shape difference of the
//    phase-aligned unit residue vectors (squared norm 2 (1 - sqrt(MAC))), and the log ratio of the residue vectors'
//    norms (the modal scaling, which fixes the absolute size of masses and stiffnesses that f and shape leave free).
// 3. The mass/stiffness parameters partitioned by Sobol total indices of each mode's objective (every mode of every
//    configuration) over the start range (those below 0.01 for every mode are kept at their prior, as are those
//    every configuration sets);
//    each subproblem (a mode's parameters against that mode's objectives) solved in turn, sweep after sweep.
// 4. Each subproblem solved by Levenberg-Marquardt from FitOptions::starts seeded starts; the spread of the optima
//    is reported (the paper's test for the global optimum).
// 5. Damping parameters (those only in C) by linear least squares on the modal damping ratios (NDD-weighted),
//    relinearised at the estimate.
//
// Needs FRF data, one frequency axis per configuration. Throws FitError (exit status 1) for time records,
// parameters that act on damping and mass/stiffness at once or on neither, and when the data show fewer modes than
// the parameters need (over all configurations). method_details["modal"] holds the configurations, the reference
// modes, the partition, the repetitions' spread,
// the damping least squares and the per-mode agreement at the estimate. No standard deviations (the objectives are
// not statistically weighted). nrmse, bic and cost are the output-error residual's at the estimate.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

FitResult fit_modal(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {});

}  // namespace mbgen
