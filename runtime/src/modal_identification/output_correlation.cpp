// Output correlations by FFT: a record's sums over N samples at many lags cost O(N log N) per channel pair
// instead of O(N lags).
#include "fft_transforms.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"

#include <stdexcept>

namespace mbgen {

std::vector<Eigen::MatrixXd> output_correlations(const ResponseData& data, Eigen::Index lags) {
  const Eigen::Index l = static_cast<Eigen::Index>(data.channels.size());
  const Eigen::Index r = static_cast<Eigen::Index>(data.references.size());
  std::vector<Eigen::MatrixXd> sums(static_cast<std::size_t>(lags), Eigen::MatrixXd::Zero(l, r));
  Eigen::VectorXd counts = Eigen::VectorXd::Zero(lags);
  for (const Eigen::MatrixXd& y : data.records) {
    const Eigen::Index n = y.rows();
    if (n < lags) throw std::invalid_argument("a record of " + std::to_string(n) + " samples is shorter than the " +
                                              std::to_string(lags) + " lags needed");
    // Zero padding to at least n + lags: the circular correlation then equals the linear one at lags < lags.
    modal_detail::RealTransforms fft(modal_detail::fast_length(n + lags));
    std::vector<Eigen::VectorXcd> spectra;
    for (Eigen::Index c = 0; c < l; ++c) spectra.push_back(fft.forward(y.col(c)));
    for (Eigen::Index i = 0; i < l; ++i)
      for (Eigen::Index j = 0; j < r; ++j) {
        const int ref = data.references[static_cast<std::size_t>(j)];
        // sum_t y_i(t + k) y_ref(t) is the inverse transform of Y_i conj(Y_ref).
        const Eigen::VectorXcd product =
            spectra[static_cast<std::size_t>(i)].cwiseProduct(spectra[static_cast<std::size_t>(ref)].conjugate());
        const Eigen::VectorXd c = fft.backward(product, lags);
        const double scale = 1.0 / static_cast<double>(modal_detail::fast_length(n + lags));
        for (Eigen::Index k = 0; k < lags; ++k) sums[static_cast<std::size_t>(k)](i, j) += scale * c[k];
      }
    for (Eigen::Index k = 0; k < lags; ++k) counts[k] += static_cast<double>(n - k);
  }
  for (Eigen::Index k = 0; k < lags; ++k) sums[static_cast<std::size_t>(k)] /= counts[k];
  return sums;
}

}  // namespace mbgen
