// Measured vs model FRFs per channel, with the measurement's standard deviation: the input of the residual
// analysis (mbgen/residuals/residual_analysis.hpp). FRF data is used as measured, its noise level from its coherence; a
// time record is first turned into FRFs by Welch H1, so both kinds of data are judged the same way. The model's side of
// a record is its simulated response through the same H1, so that the estimator's own bias (a peak lowered and widened
// by the finite resolution) is on both sides and not taken for a model error; the noise level is that of the H1 of
// the time-domain residual, from the residual power the inputs do not explain.
#pragma once

#include <mbgen/estimation/fit.hpp>
#include <mbgen/residuals/residual_analysis.hpp>

#include <vector>

namespace mbgen {

// The fit that gave the values judged: its data (the lines it saw) and the parameters it estimated.
struct FittedOn {
  const std::vector<DataSet>* data = nullptr;
  const std::vector<std::string>* estimated = nullptr;
};

// `values`: all model parameters; each data set's `# set` values are applied on top.
// With `fitted`, a measured FRF's lines that the fit did not see (the odd lines of the validation split, lines
// outside a fit band) are judged against the noise plus the model's own prediction uncertainty there: the
// variance j^H Cov j of the model's FRF, with Cov the parameters' covariance from the noise level alone (Fisher
// information over the lines fitted). A peak narrower than the fitted lines' spacing is predicted at the lines
// between them only as well as the fit fixes its frequency and damping: an mdof2 control whose second mode is
// 0.1 Hz wide, fitted on 0.5 Hz lines, read a frequency shift of 900 times the noise level there.
std::vector<ChannelResidual> channel_residuals(const Model& model, const std::vector<DataSet>& data,
                                               const Eigen::VectorXd& values, const FrfWeighting& weighting,
                                               const FittedOn& fitted = {});

}  // namespace mbgen
