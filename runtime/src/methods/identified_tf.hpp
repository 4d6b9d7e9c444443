// Step one's result of the two-step method: a black-box continuous-time transfer function per input, one common
// denominator for the input's channels. Internal header.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen::methods {

struct IdentifiedTf {
  std::string input;
  std::vector<std::string> outputs;
  Eigen::VectorXd denominator;              // ascending powers of s, monic: q + 1 entries, the last 1
  std::vector<Eigen::VectorXd> numerators;  // ascending powers of s, per output
  // Covariance of the stacked vector [denominator[0 .. q-1], numerators[0], numerators[1], ...]; empty when the
  // method cannot give one (covariance_note says why).
  Eigen::MatrixXd covariance;
  std::string covariance_note;

  int order() const { return static_cast<int>(denominator.size()) - 1; }
  // Index of numerators[channel][power] in the stacked vector.
  Eigen::Index numerator_index(std::size_t channel, int power) const {
    Eigen::Index offset = order();
    for (std::size_t c = 0; c < channel; ++c) offset += numerators[c].size();
    return offset + power;
  }
};

}  // namespace mbgen::methods
