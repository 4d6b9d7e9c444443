// `mbgen fit --method ekf`: joint estimation of the state and the parameters with an extended Kalman filter
// (Nickel 1999, Sec. 3.6.4 and 5.3.4.3; docs/methods.md, section "ekf").
//
//   FitResult r = mbgen::fit_ekf(model, records, options, EkfOptions{});
//
// The state is [q; q'; theta]: the coordinates, their velocities and the estimated parameters in the internal
// coordinates of parameterization.hpp (for a parameter bounded below by 0, theta = log(p / p_prior): a step in theta
// is a relative change). The parameters are random walks. The filter runs on the model discretised exactly at each
// record's sampling interval with its input hold (zero-order, or first-order for `# hold=none`), as
// simulate.hpp does, so the data's own convention is the filter's; its Jacobians are the exact derivatives of that
// discretisation (state_space_derivatives, discretize_derivatives: analytic, no finite differences).
// Records only (FRFs are refused with a FitError); several records are filtered one after the other, the
// parameters and their covariance carried over, each record's state starting from rest with a covariance of the
// size of the state's motion.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

struct EkfOptions {
  // Random walk of each estimated parameter: the standard deviation, relative to the parameter's value, of its
  // change accumulated over the whole data (all records' durations summed); spread evenly over the samples. Larger
  // follows a change faster and lets a constant parameter wander more (docs/methods.md: the default follows a
  // stiffness step of 15 % within about a tenth of a 2 s record). 0: constant parameters (a recursive fit).
  double drift = 0.05;
  // Prior standard deviation of each parameter, relative to its prior value.
  double initial_std = 0.3;
  // Pass 1 runs with a measurement noise estimated from the 4th differences of each output (an upper estimate when
  // the signal is oversampled); each further pass runs again from the prior with the noise that the previous
  // pass's innovations show (their mean square less the filter's own predicted part, over each record's second
  // half). 2 passes: the noise from the innovations once.
  int passes = 2;
  // The discretisation and its derivatives are recomputed when a parameter has moved by more than this (in theta,
  // i.e. relative) since they were last; in between they are extrapolated to first order with their derivatives
  // (on mdof2 and the spindle, 1e-2 gives the same estimates as 1e-3 to far below their std, 4 times faster).
  double relinearize = 1e-2;
  // Points of the parameter trajectories in method_details (decimated evenly over the samples).
  int trajectory_points = 300;
};

// method "ekf". FitResult: the parameters and covariance at the end of the data (the filter's final estimate and
// its covariance, which includes the random walk's spread), the output-error cost and NRMSE of a simulation at
// that estimate (as the output-error fit reports them), and method_details["ekf"]: the parameter trajectories
// with their std over time, the measurement noise used, and the normalised innovations. Throws FitError for FRF
// data, bad values, or a filter that leaves the model's admissible region (names the record and time).
FitResult fit_ekf(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {},
                  const EkfOptions& ekf = {});

}  // namespace mbgen
