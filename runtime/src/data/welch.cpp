// Welch H1 estimate: windowed overlapping segments, FFTW r2c transforms, averaged cross-spectral matrices.
#include "mbgen/data/welch.hpp"

#include <fftw3.h>

#include <Eigen/Dense>
#include <cmath>
#include <mutex>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/fftw_mutex.hpp"
#include "numerics/constants.hpp"

namespace mbgen {

namespace {

// A real-to-complex transform of length n with its own buffers.
class RealFft {
 public:
  explicit RealFft(Eigen::Index n) {
    in_ = fftw_alloc_real(static_cast<std::size_t>(n));
    out_ = fftw_alloc_complex(static_cast<std::size_t>(n / 2 + 1));
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    // FFTW_ESTIMATE: no timing runs, so the same plan (and bit-identical results) on every run.
    plan_ = fftw_plan_dft_r2c_1d(static_cast<int>(n), in_, out_, FFTW_ESTIMATE);
  }
  ~RealFft() {
    {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(plan_);
    }
    fftw_free(in_);
    fftw_free(out_);
  }
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  double* input() { return in_; }
  void execute() { fftw_execute(plan_); }
  std::complex<double> output(Eigen::Index k) const { return {out_[k][0], out_[k][1]}; }

 private:
  double* in_ = nullptr;
  fftw_complex* out_ = nullptr;
  fftw_plan plan_ = nullptr;
};

Eigen::VectorXd window_values(WelchWindow window, Eigen::Index n) {
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double c = std::cos(numerics::kTwoPi * static_cast<double>(i) / static_cast<double>(n));
    switch (window) {
      case WelchWindow::Hann: w[i] = 0.5 - 0.5 * c; break;
      case WelchWindow::Hamming: w[i] = 0.54 - 0.46 * c; break;
      case WelchWindow::Rectangular: w[i] = 1.0; break;
    }
  }
  return w;
}

// Samples from one segment's start to the next's.
Eigen::Index segment_step(const WelchOptions& options) {
  const Eigen::Index L = options.segment_length;
  const auto shared = static_cast<Eigen::Index>(std::llround(options.overlap * static_cast<double>(L)));
  return std::max<Eigen::Index>(1, L - shared);
}

// How much the overlap of the segments leaves the averaged spectra more variable than `segments` independent ones:
// 1 + 2 sum_{j>=1} (1 - j/K) rho_j^2 (Welch 1967), rho_j the window's overlap correlation at a shift of j steps,
// sum w[i] w[i + j step] / sum w[i]^2 (50 % overlapping Hann segments: rho_1 = 1/6, a factor of about 1.056).
double overlap_variance_factor(const Eigen::VectorXd& w, Eigen::Index step, Eigen::Index segments) {
  const Eigen::Index L = w.size();
  const double power = w.squaredNorm();
  if (!(power > 0)) return 1.0;
  double factor = 1.0;
  for (Eigen::Index j = 1; j < segments && j * step < L; ++j) {
    const Eigen::Index shift = j * step;
    const double rho = w.head(L - shift).dot(w.tail(L - shift)) / power;
    factor += 2.0 * (1.0 - static_cast<double>(j) / static_cast<double>(segments)) * rho * rho;
  }
  return factor;
}

}  // namespace

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

std::complex<double> zero_order_hold_response(double f_hz, double dt) {
  const double x = numerics::kPi * f_hz * dt;
  const double sinc = x == 0 ? 1.0 : std::sin(x) / x;
  return std::polar(sinc, -x);
}

void remove_zero_order_hold(FrfData& frf, double dt) {
  for (auto& ch : frf.channels)
    for (Eigen::Index k = 0; k < frf.f_hz.size(); ++k) ch.values[k] /= zero_order_hold_response(frf.f_hz[k], dt);
}

std::vector<double> welch_line_correlation(const WelchOptions& options, int count) {
  const Eigen::VectorXd w = window_values(options.window, options.segment_length);
  const Eigen::Index L = w.size();
  const double power = w.squaredNorm();
  std::vector<double> rho;
  for (int j = 1; j <= count; ++j) {
    std::complex<double> c = 0;
    for (Eigen::Index n = 0; n < L; ++n)
      c += w[n] * w[n] * std::polar(1.0, -numerics::kTwoPi * j * static_cast<double>(n) / static_cast<double>(L));
    rho.push_back(power > 0 ? std::norm(c / power) : 0.0);
  }
  return rho;
}

double welch_variance_dof(const WelchOptions& options, Eigen::Index segments, Eigen::Index inputs) {
  const double factor =
      overlap_variance_factor(window_values(options.window, options.segment_length), segment_step(options), segments);
  return 2.0 * static_cast<double>(std::max<Eigen::Index>(segments - inputs, 1)) / factor;
}

WelchEstimate welch_h1(const TimeRecord& record, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& outputs, const WelchOptions& options) {
  const Eigen::Index L = options.segment_length;
  const Eigen::Index n = record.samples();
  if (inputs.empty() || outputs.empty()) throw DataError(record.file, 0, 0, "Welch H1 needs at least one input and one output");
  if (L < 2) throw DataError(record.file, 0, 0, "Welch segment length must be at least 2");
  if (!(options.overlap >= 0 && options.overlap < 1))
    throw DataError(record.file, 0, 0, "Welch overlap must be in [0, 1)");
  if (n < L)
    throw DataError(record.file, 0, 0,
                    "time record has " + std::to_string(n) + " samples, fewer than one Welch segment of " +
                        std::to_string(L));
  const Eigen::Index step = segment_step(options);
  const Eigen::Index segments = 1 + (n - L) / step;
  const Eigen::Index ni = static_cast<Eigen::Index>(inputs.size()), no = static_cast<Eigen::Index>(outputs.size());
  if (segments < ni)
    throw DataError(record.file, 0, 0,
                    "Welch H1 with " + std::to_string(ni) + " inputs needs at least as many segments, the record gives " +
                        std::to_string(segments));

  std::vector<const Signal*> signals;
  for (const auto& name : inputs) signals.push_back(&record.at(name));
  for (const auto& name : outputs) signals.push_back(&record.at(name));
  const Eigen::Index m = ni + no;
  const Eigen::Index bins = L / 2 + 1;
  const Eigen::VectorXd w = window_values(options.window, L);

  // Averaged cross-spectral matrix per bin: S = sum over segments of Z Z^H, Z = (X; Y). Scale factors
  // (window power, sampling rate, one-sided doubling) cancel in H1 and coherence, so they are left out.
  std::vector<Eigen::MatrixXcd> S(static_cast<std::size_t>(bins), Eigen::MatrixXcd::Zero(m, m));
  {
    RealFft fft(L);
    Eigen::MatrixXcd Z(m, bins);
    for (Eigen::Index s = 0; s < segments; ++s) {
      const Eigen::Index start = s * step;
      for (Eigen::Index j = 0; j < m; ++j) {
        const Eigen::VectorXd& v = signals[static_cast<std::size_t>(j)]->values;
        for (Eigen::Index i = 0; i < L; ++i) fft.input()[i] = w[i] * v[start + i];
        fft.execute();
        for (Eigen::Index k = 0; k < bins; ++k) Z(j, k) = fft.output(k);
      }
      for (Eigen::Index k = 0; k < bins; ++k) S[static_cast<std::size_t>(k)].noalias() += Z.col(k) * Z.col(k).adjoint();
    }
  }

  // The noise's variance in H1 is that of `segments` / overlap factor independent averages.
  const double overlap_factor = overlap_variance_factor(w, step, segments);
  WelchEstimate est;
  est.segments = segments;
  est.dt = record.dt();
  est.frf.file = record.file;
  est.frf.set = record.set;
  std::vector<double> f;
  std::vector<Eigen::MatrixXcd> H;
  std::vector<Eigen::VectorXd> coherence;
  std::vector<Eigen::MatrixXd> variance;  // per bin: outputs x inputs
  for (Eigen::Index k = 0; k < bins; ++k) {
    const Eigen::MatrixXcd& Sk = S[static_cast<std::size_t>(k)];
    const Eigen::MatrixXcd Gxx = Sk.topLeftCorner(ni, ni);
    const Eigen::MatrixXcd Gyx = Sk.bottomLeftCorner(no, ni);
    // Singular input spectra (an input without power in this bin, or inputs fully correlated): H1 is not
    // defined, leave the bin out rather than return a meaningless number.
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>(Gxx, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(eig.maxCoeff() > 0) || eig.minCoeff() <= 1e-12 * eig.maxCoeff()) {
      est.dropped_bins.push_back(k);
      continue;
    }
    // H Gxx = Gyx with Gxx Hermitian: H^H = Gxx^{-1} Gyx^H.
    const auto Gxx_ldlt = Gxx.ldlt();
    const Eigen::MatrixXcd Hk = Gxx_ldlt.solve(Gyx.adjoint()).adjoint();
    const Eigen::VectorXd Gxx_inverse_diagonal =
        Gxx_ldlt.solve(Eigen::MatrixXcd::Identity(ni, ni)).diagonal().real();
    Eigen::VectorXd gamma(no);
    Eigen::MatrixXd var(no, ni);
    for (Eigen::Index o = 0; o < no; ++o) {
      const double gyy = Sk(ni + o, ni + o).real();
      // Multiple coherence: the part of the output power explained linearly by the inputs.
      const double explained = (Hk.row(o) * Gyx.row(o).adjoint())(0, 0).real();
      gamma[o] = gyy > 0 ? std::clamp(explained / gyy, 0.0, 1.0) : 0.0;
      // S sums the segments' spectra; the product below is the same for sums and averages, and is the variance of
      // one segment's H. Averaging divides it by the number of segments less the inputs: the unexplained power is
      // the residual of a least-squares fit of ni regressors to `segments` values, low by that ratio on average.
      // Overlapping segments are not independent: their average varies more, by the overlap factor.
      const double unexplained = std::max(gyy - explained, 0.0);
      const double degrees_of_freedom = static_cast<double>(std::max<Eigen::Index>(segments - ni, 1));
      var.row(o) = unexplained * Gxx_inverse_diagonal.transpose() * overlap_factor / degrees_of_freedom;
    }
    f.push_back(static_cast<double>(k) / (static_cast<double>(L) * est.dt));
    H.push_back(Hk);
    coherence.push_back(gamma);
    variance.push_back(var);
  }
  const Eigen::Index nf = static_cast<Eigen::Index>(f.size());
  est.frf.f_hz = Eigen::Map<const Eigen::VectorXd>(f.data(), nf);
  for (Eigen::Index o = 0; o < no; ++o)
    for (Eigen::Index i = 0; i < ni; ++i) {
      FrfChannel ch{outputs[static_cast<std::size_t>(o)], inputs[static_cast<std::size_t>(i)], Eigen::VectorXcd(nf),
                    Eigen::VectorXd(nf)};
      Eigen::VectorXd v(nf);
      for (Eigen::Index k = 0; k < nf; ++k) {
        ch.values[k] = H[static_cast<std::size_t>(k)](o, i);
        (*ch.coherence)[k] = coherence[static_cast<std::size_t>(k)][o];
        v[k] = variance[static_cast<std::size_t>(k)](o, i);
      }
      est.frf.channels.push_back(std::move(ch));
      est.variance.push_back(std::move(v));
    }
  if (options.compensate_hold && record.hold == HoldMode::ZeroOrder) {
    remove_zero_order_hold(est.frf, est.dt);
    for (Eigen::VectorXd& v : est.variance)
      for (Eigen::Index k = 0; k < nf; ++k) v[k] /= std::norm(zero_order_hold_response(est.frf.f_hz[k], est.dt));
  }
  return est;
}

}  // namespace mbgen
