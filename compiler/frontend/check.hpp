// Semantic checks of a parsed model that need no algebra: names resolve, nothing is declared twice, every body
// is connected, signals sit on bodies. Also fills the implicit points (a body's centre of mass, a ground's
// origin). What needs the equations (a singular mass matrix, an untouched coordinate) is checked by the
// symbolic stage.
#pragma once

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

// Throws ModelError at the first problem.
void check_model(ir::ModelIr& model);

}  // namespace mbgen::frontend
