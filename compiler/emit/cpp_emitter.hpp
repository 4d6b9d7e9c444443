// The C++ emitter: a SymbolicModel -> one header and one source (plus part sources with `parts`), from the
// templates templates/cpp/*.tmpl. Machine-scale models (docs/scale.md): dynamic-size matrices above
// kMaxFixedSizeCoordinates, functions of bounded size, several translation units.
//
// The generated code depends on Eigen and the runtime headers mbgen/model.hpp, mbgen/transfer_function.hpp and
// mbgen/state_space_form.hpp only (and links the runtime library, which instantiates their routines for double
// and long double). See templates/cpp/model.hpp.tmpl for what it declares (metadata, M, C, G, K, B, Cd, Cv, Ca and their
// sparse parameter Jacobians, state space, transfer-function coefficients and Jacobians, make_model()).
// Output is deterministic: no timestamps, no directories, the same text for the same input.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::emit {

struct CppEmitOptions {
  std::string namespace_name;  // empty: "mbgen_models::<model name>"
  std::string header_file;     // as #included by the source, e.g. "mdof2.hpp" (directories are dropped)
  std::string source_file;     // e.g. "mdof2.cpp" (named in comments; directories are dropped)
  std::string model_file;      // named in the banner (directories are dropped)
  std::string model_name;      // empty: the IR model's name (required when sm.model is null)
  // Functions of bounded size: a matrix or Jacobian function whose assignments exceed this many operations
  // (each assignment counting its operations before CSE, operation_count.hpp, plus one for the store) is split
  // into pieces `detail::FUNCTION_chunk_K` of at most this many each (a single larger assignment is a piece of its
  // own), each with its own CSE. 0: no bound.
  std::size_t max_function_operations = 2000;
  // Translation units: 1 writes everything to the source; N > 1 puts every matrix and Jacobian function's work
  // into pieces spread over N - 1 further sources named part_file_name(source_file, 1 .. N - 1), which compile
  // independently (in parallel), the main source declaring them.
  int parts = 1;
};

struct CppEmitResult {
  std::string header, source;
  std::vector<std::string> parts;  // the further sources, parts[k - 1] for part_file_name(source_file, k)
};

// Models with more coordinates get dynamic-size Eigen matrices: fixed-size ones beyond this compile slowly, and
// Eigen refuses them on the stack beyond 128 KB (a 2n x 2n state matrix of long double at n = 46). A model of one
// coordinate gets them too: GCC 12 at -O2 warns (-Warray-bounds, a false positive) that copying its 1 x 1
// fixed-size matrices into the runtime's dynamic ones reads 16 bytes, which fails builds with -Werror.
inline constexpr std::size_t kMaxFixedSizeCoordinates = 32;

// OUT.cpp -> OUT_partK.cpp (a name without extension gets _partK.cpp).
std::string part_file_name(const std::string& source_file, int k);

// Throws frontend::ModelError when the model's name cannot name its namespace, std::invalid_argument for options
// that cannot make valid C++ (a namespace or header name the caller should have checked: cxx_text.hpp).
CppEmitResult emit_cpp(const symbolic::SymbolicModel& sm, const CppEmitOptions& options);

// The version of mbgen (the project's), named in banners and by `mbgen --version`.
const char* mbgen_version();

}  // namespace mbgen::emit
