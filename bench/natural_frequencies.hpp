// The undamped natural frequencies [Hz] of a derived model at its nominal values (the symbolic M and K evaluated,
// a generalized symmetric eigenproblem): what the SymPy comparisons (derive_spindle, derive_chain) check against.
#pragma once

#include <Eigen/Eigenvalues>

#include <cmath>
#include <vector>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::bench {

inline double to_double(const GiNaC::ex& e, const GiNaC::exmap& values) {
  return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.subs(values))).to_double();
}

inline std::vector<double> natural_frequencies(const symbolic::SymbolicModel& sm) {
  const GiNaC::exmap values = sm.values();
  const unsigned n = sm.M.rows();
  Eigen::MatrixXd M(n, n), K(n, n);
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = 0; j < n; ++j) {
      M(i, j) = to_double(sm.M(i, j), values);
      K(i, j) = to_double(sm.K(i, j), values);
    }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  std::vector<double> f;
  for (int i = 0; i < eig.eigenvalues().size(); ++i) f.push_back(std::sqrt(eig.eigenvalues()[i]) / (2 * M_PI));
  return f;
}

}  // namespace mbgen::bench
