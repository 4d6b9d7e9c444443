// A model compared with output-only modes (docs/modal.md, "A model against output-only modes"): the identified
// modes' uncertainties from data blocks, the model's modes at the response channels, their pairing by MAC, the
// weighted modal residuals, and what an update reports. The update that fits the model to them, an estimation
// method, is mbgen/methods/operational_update.hpp.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "mbgen/model.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"

namespace mbgen {

// ---- the identified modes' uncertainties ---------------------------------------------------------------------

// Batch means: each record cut into `blocks` contiguous pieces of equal length, block b the b-th piece of every
// record, each block identified on its own with the same options; a mode of the whole record is found in a block
// when the block has a mode within the frequency criterion (the nearest, MAC above 0.9 with the whole record's
// shape). Its standard deviations are those over the
// blocks divided by sqrt(blocks found): an estimate from 1/blocks of the data varies blocks times as much as one
// from all of it. shape_std is per real component of the unit-norm shape, from the blocks' shapes scaled to the
// whole record's (complex least squares) over the 2 channels - 2 components that scaling leaves.
struct ModeUncertainty {
  double f_std_hz = 0, zeta_std = 0, shape_std = 0;
  int blocks_found = 0;  // fewer than 3: no uncertainty (NaN)
};

struct BlockUncertainty {
  int blocks = 0;
  double block_s = 0;                 // each block's duration (its pieces of all records)
  std::vector<ModeUncertainty> modes;  // per mode of the identification
};

// Throws std::invalid_argument when a block is too short for the method's lags.
BlockUncertainty block_uncertainty(const ResponseData& data, const OutputOnlyIdentification& id,
                                   const OutputOnlyOptions& options, int blocks = 8);

// ---- the model's modes at the responses, and the weighted residuals ------------------------------------------

// An identified mode as the update fits it: f, zeta and the unit-norm shape at the channels with their standard
// deviations (shape_std per real component).
struct OperationalTarget {
  double f_hz = 0, zeta = 0;
  Eigen::VectorXcd shape;
  double f_std_hz = 0, zeta_std = 0, shape_std = 0;
};

// The model's oscillating modes (Im lambda > 0, by frequency as `mbgen inspect` lists them) with their shapes
// C v at the given outputs (indices into the model's outputs; the output's kind is in C, so an acceleration's shape
// is lambda^2 times the displacement's: the same up to a complex factor). A mode the sensors do not see
// (|C v| <= 1e-9 |C| |v|: rounding error) gets a zero shape, which pairs with nothing.
struct OperationalModelModes {
  std::vector<double> f_hz, zeta;
  std::vector<Eigen::VectorXcd> shapes;
};

// Throws DynamicsError (singular M) or std::runtime_error where the model cannot be evaluated.
OperationalModelModes operational_model_modes(const Model& model, const Eigen::VectorXd& p,
                                              const std::vector<int>& outputs);

// The model's output indices of the response channels; throws std::invalid_argument naming a channel the model
// does not have as an output.
std::vector<int> model_outputs_of(const ModelInfo& info, const std::vector<std::string>& channels);

// Each target paired one to one with a model mode, greedily by the largest MAC (near-ties within 1e-6 to the
// nearest frequency); -1 for targets left over when the model has fewer oscillating modes the sensors see.
std::vector<int> pair_by_mac(const std::vector<OperationalTarget>& targets, const OperationalModelModes& model,
                             std::vector<double>* mac = nullptr);

// The weighted residuals of one target against a model mode, 1 + 2 channels of them: (f_model - f) / f_std, then
// the target's shape less the model's times the complex factor that fits it best (least squares), real and
// imaginary parts per channel, divided by shape_std. Output-only shapes have no scale, so only their direction is
// compared; the shape residual's squared norm is (1 - MAC) / shape_std^2 for unit-norm shapes.
void operational_residuals(const OperationalTarget& target, double model_f_hz, const Eigen::VectorXcd& model_shape,
                           Eigen::Ref<Eigen::VectorXd> r);
inline int operational_residuals_per_mode(int channels) { return 1 + 2 * channels; }

// ---- what an update reports ----------------------------------------------------------------------------------

struct UpdatedParameter {
  std::string name, kind;  // kind: "mass/stiffness" or "damping"
  double prior = 0, estimate = 0, std = 0;
};

// A paired mode before (model at the priors) and after the update.
struct UpdatedPair {
  int mode = 0;  // index into the identified modes
  double f_hz = 0, f_std_hz = 0, zeta = 0, zeta_std = 0, shape_std = 0;
  int model_mode_before = -1, model_mode_after = -1;
  double model_f_before = 0, model_f_after = 0, model_zeta_before = 0, model_zeta_after = 0;
  double mac_before = 0, mac_after = 0;
};

struct OperationalUpdate {
  std::string model_file;
  BlockUncertainty uncertainty;
  std::vector<UpdatedParameter> parameters;  // model order
  std::vector<UpdatedPair> pairs;
  std::vector<int> unpaired;  // identified modes left out: no model mode left, or no uncertainty
  double chi2_before = 0, chi2_after = 0;  // sum of squared weighted structural residuals
  int residuals = 0;                       // their number
  int iterations = 0;
  bool converged = false;
  std::vector<std::string> notes;
};

}  // namespace mbgen
