#include "symbolic/geometry.hpp"

#include "frontend/diagnostics.hpp"

namespace mbgen::symbolic {

GiNaC::matrix to_column(const ir::Vec3& v, const ParameterTable& params) {
  GiNaC::matrix c(3, 1);
  for (unsigned i = 0; i < 3; ++i) c(i, 0) = params.convert(v[i]);
  return c;
}

GiNaC::matrix unit_direction(const ir::Direction& d, const ParameterTable& params) {
  const GiNaC::matrix v = to_column(d.vector, params);
  const GiNaC::ex length_squared = tidy(dot(v, v));
  if (length_squared.is_zero())
    throw frontend::ModelError(params.model().file, d.loc,
                               "the direction (0, 0, 0) has no length; give a non-zero vector or x, y, z");
  const GiNaC::ex length = GiNaC::sqrt(length_squared);
  GiNaC::matrix n(3, 1);
  for (unsigned i = 0; i < 3; ++i) n(i, 0) = length == 1 ? v(i, 0) : tidy(v(i, 0) / length);
  return n;
}

GiNaC::ex dot(const GiNaC::matrix& n, const GiNaC::matrix& v) {
  return n(0, 0) * v(0, 0) + n(1, 0) * v(1, 0) + n(2, 0) * v(2, 0);
}

Row zero_row(int n) { return Row(static_cast<size_t>(n), GiNaC::ex(0)); }

Row subtract(const Row& b, const Row& a) {
  Row r(b.size());
  for (size_t i = 0; i < b.size(); ++i)
    if (!b[i].is_zero() || !a[i].is_zero()) r[i] = tidy(b[i] - a[i]);  // most of a large model's row is zero
  return r;
}

bool is_zero(const Row& r) {
  for (const GiNaC::ex& e : r)
    if (!e.is_zero()) return false;
  return true;
}

}  // namespace mbgen::symbolic
