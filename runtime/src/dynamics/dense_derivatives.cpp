#include "dense_derivatives.hpp"

namespace mbgen::detail {

std::vector<ModelMatrices> dense_derivatives(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count) {
  ModelMatrices zero;
  zero.M = Eigen::MatrixXd::Zero(m.M.rows(), m.M.cols());
  zero.C = Eigen::MatrixXd::Zero(m.C.rows(), m.C.cols());
  zero.K = Eigen::MatrixXd::Zero(m.K.rows(), m.K.cols());
  zero.B = Eigen::MatrixXd::Zero(m.B.rows(), m.B.cols());
  zero.Cd = Eigen::MatrixXd::Zero(m.Cd.rows(), m.Cd.cols());
  zero.Cv = Eigen::MatrixXd::Zero(m.Cv.rows(), m.Cv.cols());
  zero.Ca = Eigen::MatrixXd::Zero(m.Ca.rows(), m.Ca.cols());
  std::vector<ModelMatrices> result(static_cast<std::size_t>(parameter_count), zero);
  auto scatter = [&](const std::vector<DerivativeEntry>& entries, Eigen::MatrixXd ModelMatrices::*member) {
    for (const auto& e : entries) (result[static_cast<std::size_t>(e.param)].*member)(e.row, e.col) += e.value;
  };
  scatter(d.M, &ModelMatrices::M);
  scatter(d.C, &ModelMatrices::C);
  scatter(d.K, &ModelMatrices::K);
  scatter(d.B, &ModelMatrices::B);
  scatter(d.Cd, &ModelMatrices::Cd);
  scatter(d.Cv, &ModelMatrices::Cv);
  scatter(d.Ca, &ModelMatrices::Ca);
  return result;
}

}  // namespace mbgen::detail
