// The C++ emitter: a SymbolicModel -> one header and one source, from the templates templates/cpp/*.tmpl.
//
// The generated code depends on Eigen and the runtime headers mbgen/model.hpp and mbgen/transfer_function.hpp
// only. See templates/cpp/model.hpp.tmpl for what it declares (metadata, M, C, G, K, B, Cd, Cv, Ca and their
// sparse parameter Jacobians, state space, transfer-function coefficients and Jacobians, make_model()).
// Output is deterministic: no timestamps, no directories, the same text for the same input.
#pragma once

#include <string>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::emit {

struct CppEmitOptions {
  std::string namespace_name;  // empty: "mbgen_models::<model name>"
  std::string header_file;     // as #included by the source, e.g. "mdof2.hpp" (directories are dropped)
  std::string source_file;     // e.g. "mdof2.cpp" (named in comments; directories are dropped)
  std::string model_file;      // named in the banner (directories are dropped)
  std::string model_name;      // empty: the IR model's name (required when sm.model is null)
};

struct CppEmitResult {
  std::string header, source;
};

// Throws frontend::ModelError when the model's name cannot name its namespace, std::invalid_argument for options
// that cannot make valid C++ (a namespace or header name the caller should have checked: cxx_text.hpp).
CppEmitResult emit_cpp(const symbolic::SymbolicModel& sm, const CppEmitOptions& options);

// The version of mbgen (the project's), named in banners and by `mbgen --version`.
const char* mbgen_version();

}  // namespace mbgen::emit
