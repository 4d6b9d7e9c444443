// Data held back from a fit to judge it: a model that only fits noise better gets worse on data it has not seen.
//
// FRFs: the even frequency lines are fitted, the odd ones validate. Time records: the first 70 % of the samples are
// fitted; the validation simulates the whole record from rest (the state at the split is unknown, and lightly
// damped modes remember it for seconds) and scores only the last 30 %.
#pragma once

#include <mbgen/estimation/fit.hpp>

#include <vector>

namespace mbgen {

struct SplitData {
  std::vector<DataSet> fit;         // what the estimator sees
  std::vector<DataSet> validation;  // what the validation error is computed on (same order as the input)
  std::vector<Eigen::Index> scored_from;  // per validation set: first scored sample (time) or 0 (FRF)
};

SplitData split_for_validation(const std::vector<DataSet>& data, double fit_fraction = 0.7);

// sqrt(sum of squared weighted errors / sum of squared weighted measurements) over the validation data at
// `values`: FRF lines weighted by the measurement's standard deviation (as the fit weights them, frf_sigma.hpp),
// time samples per output by the output's measured RMS.
double validation_nrmse(const Model& model, const SplitData& split, const Eigen::VectorXd& values,
                        const FrfWeighting& weighting);

}  // namespace mbgen
