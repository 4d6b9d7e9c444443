// The symbolic derivation stage: ir::ModelIr -> exact equations of motion (Lagrange's method, thesis Ch. 3).
#pragma once

#include <map>
#include <string>

#include "ir/model_ir.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

struct DeriveOptions {
  std::map<std::string, std::string> set;  // --set NAME=VALUE overrides (VALUE is a decimal literal)
  bool transfer_functions = true;          // also fill transfer_functions and cancellations
};

// Derives M, C, G, C_total, K, B, Cd, Cv, Ca, the uncoupled blocks and (optionally) the transfer functions.
// The result points to `model`, which must outlive it. Throws frontend::ModelError, located at the offending IR
// node, for bad overrides, parameter cycles, unknown names, invalid spins, a coordinate no element acts on and a
// singular mass matrix.
SymbolicModel derive(const ir::ModelIr& model, const DeriveOptions& options = {});

}  // namespace mbgen::symbolic
