#include "model_checks.hpp"

#include "matrix_checks.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"

#include <sstream>
#include <vector>

namespace mbgen::detail {

void check_matrices(const ModelMatrices& m, const char* where) {
  const Eigen::Index n = m.M.rows();
  require_square(m.M, n, "M", where);
  require_square(m.C, n, "C", where);
  require_square(m.K, n, "K", where);
  require_shape(m.B, n, m.B.cols(), "B", where);
  const Eigen::Index outputs = m.Cd.rows();
  require_shape(m.Cd, outputs, n, "Cd", where);
  require_shape(m.Cv, outputs, n, "Cv", where);
  require_shape(m.Ca, outputs, n, "Ca", where);
}

namespace {
void check_entries(const std::vector<DerivativeEntry>& entries, const Eigen::MatrixXd& X, const char* name,
                   int parameter_count, const char* where) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const DerivativeEntry& e = entries[i];
    if (e.param >= 0 && e.param < parameter_count && e.row >= 0 && e.row < X.rows() && e.col >= 0 &&
        e.col < X.cols())
      continue;
    std::ostringstream msg;
    msg << where << ": derivative entry " << i << " of " << name << " (param " << e.param << ", row " << e.row
        << ", col " << e.col << ") is out of range for " << parameter_count << " parameters and a " << X.rows()
        << "x" << X.cols() << " matrix";
    throw DynamicsError(msg.str());
  }
}
}  // namespace

void check_derivatives(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count, const char* where) {
  check_entries(d.M, m.M, "M", parameter_count, where);
  check_entries(d.C, m.C, "C", parameter_count, where);
  check_entries(d.K, m.K, "K", parameter_count, where);
  check_entries(d.B, m.B, "B", parameter_count, where);
  check_entries(d.Cd, m.Cd, "Cd", parameter_count, where);
  check_entries(d.Cv, m.Cv, "Cv", parameter_count, where);
  check_entries(d.Ca, m.Ca, "Ca", parameter_count, where);
}

void check_parameter_vector(const Model& model, const Eigen::VectorXd& p, const char* where) {
  const auto expected = model.info().parameters.size();
  if (static_cast<std::size_t>(p.size()) == expected) return;
  std::ostringstream msg;
  msg << where << ": model '" << model.info().name << "' has " << expected << " parameters, got a vector of "
      << p.size();
  throw DynamicsError(msg.str());
}

}  // namespace mbgen::detail
