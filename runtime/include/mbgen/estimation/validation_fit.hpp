// How well an estimate reproduces data it was not fitted to, as MATLAB's `compare` scores it (docs/estimation.md,
// "Validation on other data"): per channel
//
//   fit % = 100 (1 - ||y - yhat|| / ||y - mean(y)||)      time records: y a measured output, yhat the simulation
//   fit % = 100 (1 - ||H - Hhat|| / ||H||)                 FRFs: complex values over the lines, no mean removed
//
// 100 is a perfect match; 0 is no better than the baseline (the record's mean, or a zero FRF); it can be negative.
#pragma once

#include "mbgen/data/data_set.hpp"
#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen {

struct ChannelValidation {
  std::string channel;     // a record's output, or an FRF's OUTPUT/INPUT
  double fit_percent = 0;  // NaN when the baseline's norm is zero (a constant record, an all-zero FRF)
};

struct ValidationScore {
  std::string file;
  bool frf = false;
  std::vector<ChannelValidation> channels;  // in the order the fit's report draws them
};

// The fit percentage of `model` against `measured`; `subtract_mean`: the baseline is the measured mean (records)
// or zero (FRFs).
double compare_fit_percent(const Eigen::VectorXcd& measured, const Eigen::VectorXcd& model, bool subtract_mean);

// Throws FitError (naming the file) unless the fit could take every data set: FRF channels of model outputs and
// inputs, records with every model input, some model output and two samples. Simulates nothing: a check of
// validation data before the fit.
void check_validation_data(const Model& model, const std::vector<DataSet>& data);

// Every data set scored with the model at `values` (all model parameters; each set's `# set` values on top).
std::vector<ValidationScore> validation_scores(const Model& model, const std::vector<DataSet>& data,
                                               const Eigen::VectorXd& values);

}  // namespace mbgen
