// JSON values of the modal documents (modal_json.cpp, output_only_json.cpp): NaN and infinities are not JSON numbers
// and are written as null. Internal header.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>

namespace mbgen::modal_json_values {

inline nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

inline nlohmann::json complex_number(std::complex<double> z) {
  return nlohmann::json::array({number(z.real()), number(z.imag())});
}

inline nlohmann::json matrix(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(number(m(i, j)));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace mbgen::modal_json_values
