// `mbgen export --format mat`: the JSON export's content (docs/interfaces.md, "mbgen-export/1") as MATLAB variables.
#pragma once

#include <mbgen/dynamics/frf.hpp>
#include <mbgen/model.hpp>

#include <string>

namespace mbgen::cli {

// The .mat bytes for `what` (matrices, state-space, modes or frf; `frf` needed for frf), at parameter values `p`
// with the matrices `m` there. Deterministic: the same input gives the same bytes. Variables: schema, model, what,
// parameter_names (cell) and parameter_values, coordinates, inputs, outputs (cells); then M, C, K, B, Cd, Cv, Ca;
// or A, B, C, D; or f_hz, zeta, eigenvalue (one row per mode) and shape (coordinates x modes, complex); or f_hz
// (lines x 1) and H (lines x outputs x inputs, complex).
std::string export_mat(const std::string& model_path, const std::string& what, const ModelInfo& info,
                       const Eigen::VectorXd& p, const ModelMatrices& m, const FrfResult* frf);

}  // namespace mbgen::cli
