// How a model's modes depend on its parameters (docs/sensitivity.md):
//
//   local_sensitivity   derivatives of each mode's frequency and damping ratio with respect to every parameter,
//                       exact (first-order eigenvalue perturbation of the state matrix), and normalized
//                       (p / f) df/dp, (p / zeta) dzeta/dp
//   mode_visibility     which output/input channel sees each mode best
//   sobol_indices       first-order and total Sobol indices of any function of [0, 1)^k, Saltelli/Jansen
//                       estimators, seeded, on several threads, deterministic
//   global_sensitivity  Sobol indices of the modes' f and zeta over ranges of the parameters
//   feature_map         each mode's (f, zeta) as one parameter sweeps
//
// "Modes" here are the oscillating ones (complex-conjugate pairs), in the order of modal_analysis; they are
// followed through parameter changes by MAC of their displacement shapes.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/model.hpp"

namespace mbgen {

// The oscillating modes of the model at p (modal_analysis's, without the real-eigenvalue ones).
std::vector<Mode> oscillating_modes(const Model& model, const Eigen::VectorXd& p);

// For each mode of `reference`, the index of the mode of `modes` it continues (largest MAC of the displacement
// shapes, assigned greedily by MAC), or -1 when `modes` has too few.
std::vector<int> track_modes(const std::vector<Mode>& reference, const std::vector<Mode>& modes);

// ---- local ----------------------------------------------------------------------------------------------------

struct LocalSensitivity {
  std::vector<std::string> parameters;  // every parameter of the model, in model order
  Eigen::VectorXd values;               // p
  std::vector<Mode> modes;              // oscillating modes at p
  Eigen::MatrixXd df_dp, dzeta_dp;      // modes x parameters: Hz per unit, 1 per unit
  Eigen::MatrixXd f_normalized;         // (p / f) df/dp: relative change of f per relative change of p
  Eigen::MatrixXd zeta_normalized;      // (p / zeta) dzeta/dp; NaN where zeta = 0
};

// dlambda/dp = w^T (dA/dp) v / (w^T v) for each eigenvalue (v, w right and left eigenvectors of A).
LocalSensitivity local_sensitivity(const Model& model, const Eigen::VectorXd& p);

// ---- visibility ----------------------------------------------------------------------------------------------

// Per mode and output/input channel (output-major: channel o * inputs + i): how much of the channel's response at
// the mode's frequency is that mode's term, |R/(i w - lambda) + conj(R)/(i w - conj(lambda))| / |H(i w)|, and the
// term's magnitude itself.
struct ModeVisibility {
  std::vector<std::string> channels;  // "OUTPUT/INPUT"
  Eigen::MatrixXd dominance;          // modes x channels, 0..~1
  Eigen::MatrixXd peak;               // modes x channels, |modal term| at the mode's frequency (output units)
  std::vector<int> best;              // per mode, the channel of largest dominance
};

ModeVisibility mode_visibility(const Model& model, const Eigen::VectorXd& p);

// ---- Sobol indices -------------------------------------------------------------------------------------------

struct SobolOptions {
  int samples = 1024;  // N: the estimators use N (k + 2) evaluations
  std::uint64_t seed = 1;
  int threads = 2;
};

struct SobolIndices {
  Eigen::MatrixXd first, total;          // outputs x inputs: S_i (Saltelli 2010) and S_Ti (Jansen 1999)
  Eigen::MatrixXd first_std, total_std;  // their standard errors (CLT over the N terms, variance held fixed)
  Eigen::VectorXd mean, variance;        // per output, over the 2N points of A and B
  Eigen::VectorXi used;                  // per output, samples where every evaluation was finite
  int evaluations = 0;
};

// `f` maps a point of [0, 1)^dimensions to `outputs` values (NaN for "undefined here": such samples are left out
// of that output's estimates). Points come from a 64-bit Mersenne twister seeded with `seed`, as doubles
// (x >> 11) 2^-53; results do not depend on the number of threads. `f` is called from several threads at once.
SobolIndices sobol_indices(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, int dimensions, int outputs,
                           const SobolOptions& options = {});

// ---- over the model's parameters -----------------------------------------------------------------------------

struct ParameterRange {
  std::string name;
  int index = 0;  // into the model's parameters
  double lo = 0, hi = 0;
};

// The parameters to vary: the `estimate` ones (all parameters when there are none), each uniform over
// value * [1 - spread, 1 + spread] cut to its bounds, or over its bounds when `use_bounds` (both finite; an
// error otherwise). Throws std::invalid_argument.
std::vector<ParameterRange> parameter_ranges(const ModelInfo& info, const Eigen::VectorXd& p, double spread,
                                             bool use_bounds);

struct GlobalSensitivity {
  std::vector<ParameterRange> ranges;
  std::vector<Mode> nominal;  // the modes at p, which the samples' modes are matched to
  SobolIndices f, zeta;       // outputs = nominal modes, inputs = ranges
};

GlobalSensitivity global_sensitivity(const Model& model, const Eigen::VectorXd& p,
                                     const std::vector<ParameterRange>& ranges, const SobolOptions& options = {});

// ---- feature maps --------------------------------------------------------------------------------------------

struct FeatureMap {
  std::string parameter;
  Eigen::VectorXd values;      // the sweep, lo..hi in `points` steps
  Eigen::MatrixXd f_hz, zeta;  // points x traces; NaN where a trace was lost
  std::vector<Mode> start;     // the modes at the first value, one trace each
};

// Each mode followed (by MAC, step to step) while parameter `index` sweeps lo..hi (points >= 2), others at p.
FeatureMap feature_map(const Model& model, const Eigen::VectorXd& p, int index, double lo, double hi, int points);

}  // namespace mbgen
