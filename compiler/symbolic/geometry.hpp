// Small exact-geometry helpers shared by the derivation steps (internal).
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "ir/model_ir.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::symbolic {

// The canonical form every matrix entry is kept in, so that equal entries compare equal.
inline GiNaC::ex tidy(const GiNaC::ex& e) { return GiNaC::normal(GiNaC::expand(e)); }

// Column vector (3x1) of an IR point.
GiNaC::matrix to_column(const ir::Vec3& v, const ParameterTable& params);
// Unit vector (3x1) of an IR direction; a zero vector is a ModelError at the direction.
GiNaC::matrix unit_direction(const ir::Direction& d, const ParameterTable& params);
// n^T v for 3x1 columns.
GiNaC::ex dot(const GiNaC::matrix& n, const GiNaC::matrix& v);

// A linear form over the generalized coordinates (one entry per coordinate), e.g. n^T dr_p/dq at q = 0.
using Row = std::vector<GiNaC::ex>;
Row zero_row(int n);
Row subtract(const Row& b, const Row& a);
bool is_zero(const Row& r);

}  // namespace mbgen::symbolic
