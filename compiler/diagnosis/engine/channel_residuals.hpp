// Measured vs model FRFs per channel, with the measurement's standard deviation: the input of the residual
// analysis (mbgen/residual_analysis.hpp). FRF data is used as measured, its noise level from its coherence; a time
// record is first turned into FRFs by Welch H1, so both kinds of data are judged the same way. The model's side of a
// record is its simulated response through the same H1, so that the estimator's own bias (a peak lowered and widened
// by the finite resolution) is on both sides and not taken for a model error; the noise level is that of the H1 of
// the time-domain residual, from the residual power the inputs do not explain.
#pragma once

#include <mbgen/fit.hpp>
#include <mbgen/residual_analysis.hpp>

#include <vector>

namespace mbgen::diagnosis {

// `values`: all model parameters; each data set's `# set` values are applied on top.
std::vector<ChannelResidual> channel_residuals(const Model& model, const std::vector<DataSet>& data,
                                               const Eigen::VectorXd& values, const FrfWeighting& weighting);

}  // namespace mbgen::diagnosis
