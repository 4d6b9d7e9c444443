// Real FFTs through FFTW for the output-only methods (correlations, spectral matrices).
#pragma once

#include <Eigen/Core>
#include <fftw3.h>

#include <complex>
#include <mutex>

#include "mbgen/data/fftw_mutex.hpp"

namespace mbgen::modal_detail {

// FFTW buffers and plans of one transform length, forward (real to half spectrum) and back.
class RealTransforms {
 public:
  explicit RealTransforms(Eigen::Index n) : n_(n) {
    real_ = fftw_alloc_real(static_cast<std::size_t>(n));
    spectrum_ = fftw_alloc_complex(static_cast<std::size_t>(n / 2 + 1));
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    forward_ = fftw_plan_dft_r2c_1d(static_cast<int>(n), real_, spectrum_, FFTW_ESTIMATE);
    backward_ = fftw_plan_dft_c2r_1d(static_cast<int>(n), spectrum_, real_, FFTW_ESTIMATE);
  }
  ~RealTransforms() {
    {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(forward_);
      fftw_destroy_plan(backward_);
    }
    fftw_free(real_);
    fftw_free(spectrum_);
  }
  RealTransforms(const RealTransforms&) = delete;
  RealTransforms& operator=(const RealTransforms&) = delete;

  // Half spectrum of x zero-padded to n.
  Eigen::VectorXcd forward(const Eigen::VectorXd& x) {
    for (Eigen::Index k = 0; k < n_; ++k) real_[k] = k < x.size() ? x[k] : 0.0;
    fftw_execute(forward_);
    Eigen::VectorXcd out(n_ / 2 + 1);
    for (Eigen::Index k = 0; k < out.size(); ++k) out[k] = {spectrum_[k][0], spectrum_[k][1]};
    return out;
  }
  // The first `count` samples of the inverse transform of a half spectrum (unnormalized, as FFTW's).
  Eigen::VectorXd backward(const Eigen::VectorXcd& half, Eigen::Index count) {
    for (Eigen::Index k = 0; k < half.size(); ++k) {
      spectrum_[k][0] = half[k].real();
      spectrum_[k][1] = half[k].imag();
    }
    fftw_execute(backward_);
    return Eigen::Map<Eigen::VectorXd>(real_, count);
  }

 private:
  Eigen::Index n_;
  double* real_ = nullptr;
  fftw_complex* spectrum_ = nullptr;
  fftw_plan forward_ = nullptr, backward_ = nullptr;
};

inline Eigen::Index fast_length(Eigen::Index n) {  // a power of two >= n
  Eigen::Index p = 1;
  while (p < n) p *= 2;
  return p;
}

}  // namespace mbgen::modal_detail
