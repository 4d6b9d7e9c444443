// Helpers shared by the symbolic stage's tests: loading examples and evaluating exact results numerically.
#pragma once

#include <Eigen/Dense>
#include <ginac/ginac.h>

#include <string>

#include "frontend/parser.hpp"
#include "symbolic/symbolic_model.hpp"
#include "mbgen_test/paths.hpp"

namespace mbgen::symbolic::test {

inline ir::ModelIr load_example(const std::string& name) {
  return frontend::parse_file(std::string(mbgen_source_dir()) + "/examples/" + name + "/" + name + ".mdl");
}

inline double to_double(const GiNaC::ex& e, const GiNaC::exmap& values = {}) {
  const GiNaC::ex v = GiNaC::evalf(e.subs(values));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::runtime_error("not a number after substitution");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

inline Eigen::MatrixXd to_eigen(const GiNaC::matrix& m, const GiNaC::exmap& values) {
  Eigen::MatrixXd r(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) r(i, j) = to_double(m(i, j), values);
  return r;
}

inline bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return GiNaC::normal(a - b).is_zero(); }

inline bool same(const GiNaC::matrix& a, const GiNaC::matrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j)
      if (!same(a(i, j), b(i, j))) return false;
  return true;
}

inline GiNaC::ex symbol_of(const SymbolicModel& sm, const std::string& name) {
  const int i = sm.parameter_index(name);
  if (i < 0) throw std::runtime_error("no parameter " + name);
  return sm.parameters[i].sym;
}

// Maps the parameter symbols of `from` to the same-named symbols of `to` (each derivation makes its own symbols).
inline GiNaC::exmap rename_symbols(const SymbolicModel& from, const SymbolicModel& to) {
  GiNaC::exmap m;
  for (const FreeParameter& p : from.parameters) m[p.sym] = symbol_of(to, p.name);
  return m;
}

inline GiNaC::matrix substituted(const GiNaC::matrix& a, const GiNaC::exmap& m) {
  GiNaC::matrix r(a.rows(), a.cols());
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) r(i, j) = a(i, j).subs(m);
  return r;
}

}  // namespace mbgen::symbolic::test
