// Identified modes against a model's: the model's modes with their residues at the measured channels, and the
// pairing by MAC of the residue vectors (docs/modal.md).
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/model.hpp"

namespace mbgen {

// The model's modes as `mbgen inspect` lists them: one per complex-conjugate pair (positive frequency) and one
// per real eigenvalue, sorted by frequency, then damping. residues(r, c) is the residue of the model's FRF of
// data channel c at mode r (of the output the model defines: displacement, velocity or acceleration).
struct ModelModes {
  std::vector<double> f_hz, zeta;
  std::vector<std::complex<double>> lambda;
  Eigen::MatrixXcd residues;  // modes x data channels
  Eigen::MatrixXcd shapes;    // coordinates x modes: the displacement part of each mode's right eigenvector
  // What the measured channels are in the model: all outputs displacements, velocities or accelerations
  // (Unknown when mixed).
  FrfQuantity quantity = FrfQuantity::Unknown;
};

// Throws std::invalid_argument when a channel's output or input is not one of the model's.
ModelModes model_modes(const Model& model, const Eigen::VectorXd& parameters, const ModalData& data);

struct ModePairing {
  Eigen::MatrixXd mac;          // identified x model modes
  std::vector<int> model_mode;  // per identified mode, the model mode of largest MAC
  std::vector<double> best_mac;
  // Per identified mode: another identified mode has the same model mode. With few channels the shapes of
  // different modes can look alike (e.g. a torsion mode seen by sensors on one line); the model may lack a mode.
  std::vector<bool> shared;
};

ModePairing pair_modes(const std::vector<IdentifiedMode>& identified, const ModelModes& model);

}  // namespace mbgen
