// The modal method's comparison of a model's modes with reference modes identified from FRFs
// (docs/methods.md#modal). Internal header.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/model.hpp"

namespace mbgen::methods {

// The model's oscillating modes at p paired one to one with the reference modes, greedily by the largest MAC of the
// residue vectors at the measured channels times the ratio of their norms (smaller over larger): the paper pairs by
// its shape criterion; the norm ratio keeps modes the sensors hardly see from pairing by a chance MAC.
struct ModalComparison {
  bool ok = false;              // false: the model cannot be evaluated at p, or has fewer oscillating modes
  std::vector<int> model_mode;  // per reference mode: index into the model's oscillating modes
  std::vector<double> f_hz, zeta, mac;
  std::vector<Eigen::VectorXcd> residues;  // the paired model modes' residues at the data's channels
};

ModalComparison compare_modes(const Model& model, const Eigen::VectorXd& p, const ModalData& data,
                              const std::vector<IdentifiedMode>& reference);

// Real objectives per mode: 1 (frequency) + 2 channels (shape) + 1 (scale).
inline int residuals_per_mode(int channels) { return 2 + 2 * channels; }
// Of those, how many are independent (what they can determine): frequency, channels - 1 shape ratios, scale.
inline int information_per_mode(int channels) { return channels + 1; }

// The objectives of the reference modes `modes`, stacked: NFD (f - f_ref) / f_ref; the difference of the
// phase-aligned unit residue vectors (its squared norm is 2 (1 - sqrt(MAC))); log(|R| / |R_ref|).
void structural_residuals(const ModalComparison& c, const std::vector<IdentifiedMode>& reference,
                          const std::vector<int>& modes, Eigen::VectorXd& r);

}  // namespace mbgen::methods
