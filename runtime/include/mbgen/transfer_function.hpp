// Transfer-function coefficients of M q'' + C q' + K q = b u, y = (cd + s cv + s^2 ca) q, computed numerically,
// for the (output, input) pairs whose coefficients are too large to expand symbolically.
//
//   G(s) = N(s) / D(s),   D(s) = det P(s),  N(s) = c(s) adj(P(s)) b = -det [[P(s), b], [c(s), 0]],
//   P(s) = M s^2 + C s + K restricted to the uncoupled block the pair lives in (its coordinate indices).
//
// Both polynomials have degree <= 2 nb (nb = block size). They are evaluated at N = 2 nb + 1 points on a circle
// s_j = rho exp(i theta_j), theta_j = 2 pi (j + 1/2) / N (complex LU determinants), and the coefficients follow
// from an inverse DFT, unscaled by rho^k. The radius rho = (det K_b / det M_b)^(1/(2 nb)) (the geometric mean of
// the undamped natural frequencies) keeps the scaled coefficients a_k rho^k of similar size, which is what
// makes the DFT accurate; the half-step angle offset keeps the samples off the real axis, where overdamped or
// rigid-body poles sit. Coefficients are returned in ascending powers of s, divided by the leading denominator
// coefficient (det M_b), so the denominator is monic.
//
// Parameter Jacobians: for each parameter the derivatives of the matrices are given (dense, full size); the
// derivative of each determinant sample is d det P = det P * trace(P^-1 dP) (and the product rule on
// N = det P * c P^-1 b for the numerator), written with linear solves; the same inverse DFT gives the
// derivatives of the unnormalised coefficients, and the quotient rule handles the normalisation by det M_b.
//
// Header-only, templated on Scalar (double, long double; any type for which std::complex<Scalar> and Eigen's LU
// work). Needs Eigen only.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace mbgen {

template <typename Scalar>
using DenseMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
template <typename Scalar>
using DenseVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
template <typename Scalar>
using DenseRowVector = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>;

// One (output, input) pair of a system, as full-size matrices; `block` selects the coordinates it lives in.
template <typename Scalar>
struct TransferFunctionSystem {
  DenseMatrix<Scalar> M, C, K;   // n x n
  DenseRowVector<Scalar> cd, cv, ca;  // 1 x n output row
  DenseVector<Scalar> b;         // n x 1 input column
};

template <typename Scalar>
struct TransferFunctionCoefficients {
  std::vector<Scalar> numerator;    // ascending powers of s, 2 nb + 1 entries
  std::vector<Scalar> denominator;  // ascending powers of s, 2 nb + 1 entries, last = 1
};

// d numerator[k] / d p_j = numerator[j][k], likewise for the denominator (whose last entry has derivative 0).
template <typename Scalar>
struct TransferFunctionJacobian {
  std::vector<std::vector<Scalar>> numerator, denominator;
};

namespace detail {

template <typename Scalar>
DenseMatrix<Scalar> block_of(const DenseMatrix<Scalar>& A, const std::vector<int>& block) {
  const Eigen::Index nb = static_cast<Eigen::Index>(block.size());
  DenseMatrix<Scalar> out(nb, nb);
  for (Eigen::Index i = 0; i < nb; ++i)
    for (Eigen::Index j = 0; j < nb; ++j) out(i, j) = A(block[static_cast<std::size_t>(i)], block[static_cast<std::size_t>(j)]);
  return out;
}

template <typename Scalar, typename Vec>
DenseVector<Scalar> entries_of(const Vec& v, const std::vector<int>& block) {
  DenseVector<Scalar> out(static_cast<Eigen::Index>(block.size()));
  for (std::size_t i = 0; i < block.size(); ++i) out[static_cast<Eigen::Index>(i)] = v[block[i]];
  return out;
}

template <typename Scalar>
Scalar pi() {
  using std::atan;
  return Scalar(4) * atan(Scalar(1));
}

// A number as mantissa * 2^exponent: determinants of hundreds of rows (det K of a 96-coordinate chain is about
// 1e630) overflow every floating type's exponent long before their mantissas lose anything. Scaling by powers of
// two is exact, so a product formed this way rounds exactly like the plain one wherever that one is finite.
template <typename T>
struct Scaled {
  T mantissa;
  long exponent = 0;
};

template <typename Scalar>
long exponent_of(Scalar x) {
  using std::frexp;
  int e = 0;
  frexp(x, &e);
  return e;
}

template <typename Scalar>
void normalize(Scaled<Scalar>& x) {
  using std::abs;
  using std::ldexp;
  if (x.mantissa == Scalar(0)) return;
  const long e = exponent_of(abs(x.mantissa));
  x.mantissa = ldexp(x.mantissa, static_cast<int>(-e));
  x.exponent += e;
}

template <typename Scalar>
void normalize(Scaled<std::complex<Scalar>>& x) {
  using std::abs;
  using std::ldexp;
  const Scalar big = std::max(abs(x.mantissa.real()), abs(x.mantissa.imag()));
  if (big == Scalar(0)) return;
  const long e = exponent_of(big);
  x.mantissa = {ldexp(x.mantissa.real(), static_cast<int>(-e)), ldexp(x.mantissa.imag(), static_cast<int>(-e))};
  x.exponent += e;
}

// The determinant of an LU factorization, scaled: the pivots' product with the permutation's sign.
template <typename Matrix>
Scaled<typename Matrix::Scalar> scaled_determinant(const Eigen::PartialPivLU<Matrix>& lu) {
  using T = typename Matrix::Scalar;
  Scaled<T> d{T(lu.permutationP().determinant()), 0};
  const Matrix& f = lu.matrixLU();
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    d.mantissa *= f(i, i);
    normalize(d);
  }
  return d;
}

// log |x| of a scaled real number.
template <typename Scalar>
Scalar log_abs(const Scaled<Scalar>& x) {
  using std::abs;
  using std::log;
  return log(abs(x.mantissa)) + Scalar(x.exponent) * log(Scalar(2));
}

// Frequency scale of the block: (|det K| / |det M|)^(1/(2 nb)) (from scaled determinants: finite however large
// the block), with fallbacks for singular K (rigid-body motion): sqrt(trace K / trace M), then 1.
template <typename Scalar>
Scalar frequency_scale(const DenseMatrix<Scalar>& Mb, const DenseMatrix<Scalar>& Kb) {
  using std::abs;
  using std::exp;
  using std::isfinite;
  using std::sqrt;
  const Scaled<Scalar> dm = scaled_determinant(Eigen::PartialPivLU<DenseMatrix<Scalar>>(Mb));
  const Scaled<Scalar> dk = scaled_determinant(Eigen::PartialPivLU<DenseMatrix<Scalar>>(Kb));
  const Scalar n2 = Scalar(2 * Mb.rows());
  if (dm.mantissa != Scalar(0) && dk.mantissa != Scalar(0)) {
    const Scalar rho = exp((log_abs(dk) - log_abs(dm)) / n2);
    if (isfinite(rho) && rho > Scalar(0)) return rho;
  }
  const Scalar tm = abs(Mb.trace()), tk = abs(Kb.trace());
  if (tm > Scalar(0) && tk > Scalar(0)) return sqrt(tk / tm);
  return Scalar(1);
}

// Evaluation points, and the inverse DFT that turns samples f(s_j) of a polynomial of degree < N into its
// coefficients: a_k = rho^-k e^{-i k phi} / N * sum_j f_j e^{-2 pi i j k / N}, phi = pi / N.
template <typename Scalar>
struct CircleSampling {
  int N = 0;
  Scalar rho;
  std::vector<std::complex<Scalar>> points;
  std::vector<std::complex<Scalar>> roots;  // e^{-2 pi i m / N}, m = 0..N-1

  CircleSampling(int n, Scalar radius) : N(n), rho(radius) {
    using std::cos;
    using std::sin;
    const Scalar two_pi = Scalar(2) * pi<Scalar>();
    for (int m = 0; m < N; ++m) {
      const Scalar a = two_pi * Scalar(m) / Scalar(N);
      roots.emplace_back(cos(a), -sin(a));
      const Scalar theta = two_pi * (Scalar(m) + Scalar(1) / Scalar(2)) / Scalar(N);
      points.emplace_back(rho * cos(theta), rho * sin(theta));
    }
  }

  // a_k rho^k (the coefficients of f(rho sigma) in sigma = s / rho): of similar size for a well chosen rho.
  std::vector<Scalar> scaled_coefficients(const std::vector<std::complex<Scalar>>& samples) const {
    using std::cos;
    using std::sin;
    std::vector<Scalar> a(static_cast<std::size_t>(N));
    const Scalar phi = pi<Scalar>() / Scalar(N);
    for (int k = 0; k < N; ++k) {
      std::complex<Scalar> sum(0, 0);
      for (int j = 0; j < N; ++j) sum += samples[static_cast<std::size_t>(j)] * roots[static_cast<std::size_t>((j * k) % N)];
      const std::complex<Scalar> shift(cos(Scalar(k) * phi), -sin(Scalar(k) * phi));
      a[static_cast<std::size_t>(k)] = (sum * shift).real() / Scalar(N);
    }
    return a;
  }

  std::vector<Scalar> coefficients(const std::vector<std::complex<Scalar>>& samples) const {
    using std::cos;
    using std::sin;
    std::vector<Scalar> a(static_cast<std::size_t>(N));
    const Scalar phi = pi<Scalar>() / Scalar(N);
    Scalar scale = Scalar(1);  // rho^k
    for (int k = 0; k < N; ++k) {
      std::complex<Scalar> sum(0, 0);
      for (int j = 0; j < N; ++j) sum += samples[static_cast<std::size_t>(j)] * roots[static_cast<std::size_t>((j * k) % N)];
      const std::complex<Scalar> shift(cos(Scalar(k) * phi), -sin(Scalar(k) * phi));
      a[static_cast<std::size_t>(k)] = (sum * shift).real() / (Scalar(N) * scale);
      scale *= rho;
    }
    return a;
  }
};

template <typename Scalar>
using ComplexMatrix = Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, Eigen::Dynamic>;

// P(s) on the block, and the bordered matrix Q(s) = [[P, b], [c(s), 0]].
template <typename Scalar>
struct BlockSystem {
  DenseMatrix<Scalar> M, C, K;
  DenseVector<Scalar> cd, cv, ca, b;

  ComplexMatrix<Scalar> P(const std::complex<Scalar>& s) const {
    return (M.template cast<std::complex<Scalar>>() * (s * s) + C.template cast<std::complex<Scalar>>() * s +
            K.template cast<std::complex<Scalar>>());
  }
  ComplexMatrix<Scalar> Q(const std::complex<Scalar>& s) const {
    const Eigen::Index nb = M.rows();
    ComplexMatrix<Scalar> q = ComplexMatrix<Scalar>::Zero(nb + 1, nb + 1);
    q.topLeftCorner(nb, nb) = P(s);
    q.topRightCorner(nb, 1) = b.template cast<std::complex<Scalar>>();
    q.bottomLeftCorner(1, nb) =
        (cd.template cast<std::complex<Scalar>>() + cv.template cast<std::complex<Scalar>>() * s +
         ca.template cast<std::complex<Scalar>>() * (s * s))
            .transpose();
    return q;
  }
};

template <typename Scalar>
BlockSystem<Scalar> restrict_to_block(const TransferFunctionSystem<Scalar>& sys, const std::vector<int>& block) {
  const Eigen::Index n = sys.M.rows();
  if (sys.M.cols() != n || sys.C.rows() != n || sys.C.cols() != n || sys.K.rows() != n || sys.K.cols() != n ||
      sys.cd.size() != n || sys.cv.size() != n || sys.ca.size() != n || sys.b.size() != n)
    throw std::invalid_argument("transfer_function_coefficients: inconsistent matrix sizes");
  if (block.empty()) throw std::invalid_argument("transfer_function_coefficients: empty block");
  for (int i : block)
    if (i < 0 || i >= n) throw std::invalid_argument("transfer_function_coefficients: block index out of range");
  return {block_of(sys.M, block), block_of(sys.C, block), block_of(sys.K, block),
          entries_of<Scalar>(sys.cd, block), entries_of<Scalar>(sys.cv, block), entries_of<Scalar>(sys.ca, block),
          entries_of<Scalar>(sys.b, block)};
}

}  // namespace detail

namespace detail {

// rho^j as a scaled number: rho = m 2^e, m in [0.5, 1), so m^j stays representable for any block size here.
template <typename Scalar>
Scaled<Scalar> scaled_power(Scalar rho, int j) {
  using std::frexp;
  using std::pow;
  int e = 0;
  const Scalar m = frexp(rho, &e);
  Scaled<Scalar> r{pow(m, Scalar(j)), static_cast<long>(e) * j};
  normalize(r);
  return r;
}

// Coefficients in sigma of sum_k c_k sigma^k = f(rho sigma) / (det M_b rho^n) from scaled samples of f: finite for
// any block size (the samples are brought to a common exponent first; those far below the largest underflow to
// zero, as they would be lost in the sum anyway).
template <typename Scalar>
std::vector<Scalar> normalized_coefficients(const CircleSampling<Scalar>& circle,
                                            const std::vector<Scaled<std::complex<Scalar>>>& samples,
                                            const Scaled<Scalar>& lead_rho_n) {
  using std::ldexp;
  long top = std::numeric_limits<long>::min();
  for (const auto& x : samples)
    if (x.mantissa != std::complex<Scalar>(0)) top = std::max(top, x.exponent);
  std::vector<std::complex<Scalar>> f;
  for (const auto& x : samples) {
    const long shift = x.mantissa == std::complex<Scalar>(0) ? 0 : x.exponent - top;
    const int e = static_cast<int>(std::max<long>(shift, -100000));
    f.emplace_back(ldexp(x.mantissa.real(), e), ldexp(x.mantissa.imag(), e));
  }
  std::vector<Scalar> c = circle.scaled_coefficients(f);
  if (top == std::numeric_limits<long>::min()) return c;  // all samples zero
  const long e = top - lead_rho_n.exponent;
  for (auto& x : c) x = ldexp(x / lead_rho_n.mantissa, static_cast<int>(std::max<long>(std::min<long>(e, 100000), -100000)));
  return c;
}

}  // namespace detail

// The pair's transfer function in the normalised variable sigma = s / rho, G(s) = N(sigma) / D(sigma), rho the
// block's frequency scale (the geometric mean of its undamped natural frequencies), D monic: the coefficients are
// of moderate size at any block size, where those in s are not (a_0 of a 96-coordinate chain, the product of the
// squared natural frequencies, is about 1e630: beyond double, within long double). All determinants are formed
// as mantissa and exponent (detail::Scaled), so nothing overflows on the way.
template <typename Scalar>
struct ScaledTransferFunction {
  Scalar rho = Scalar(1);
  std::vector<Scalar> numerator;    // ascending powers of sigma, 2 nb + 1 entries
  std::vector<Scalar> denominator;  // ascending powers of sigma, 2 nb + 1 entries, last = 1
};

// Throws std::invalid_argument for inconsistent sizes and std::domain_error when det M_b = 0.
template <typename Scalar>
ScaledTransferFunction<Scalar> transfer_function_scaled(const TransferFunctionSystem<Scalar>& sys,
                                                        const std::vector<int>& block) {
  using Complex = std::complex<Scalar>;
  const detail::BlockSystem<Scalar> bs = detail::restrict_to_block(sys, block);
  const int nb = static_cast<int>(block.size());
  const detail::CircleSampling<Scalar> circle(2 * nb + 1, detail::frequency_scale(bs.M, bs.K));
  std::vector<detail::Scaled<Complex>> den_samples, num_samples;
  for (const auto& s : circle.points) {
    den_samples.push_back(detail::scaled_determinant(Eigen::PartialPivLU<detail::ComplexMatrix<Scalar>>(bs.P(s))));
    detail::Scaled<Complex> q =
        detail::scaled_determinant(Eigen::PartialPivLU<detail::ComplexMatrix<Scalar>>(bs.Q(s)));
    q.mantissa = -q.mantissa;
    num_samples.push_back(q);
  }
  const detail::Scaled<Scalar> lead = detail::scaled_determinant(Eigen::PartialPivLU<DenseMatrix<Scalar>>(bs.M));
  if (lead.mantissa == Scalar(0)) throw std::domain_error("transfer_function_coefficients: singular mass matrix block");
  const detail::Scaled<Scalar> rho_n = detail::scaled_power(circle.rho, 2 * nb);
  detail::Scaled<Scalar> lead_rho_n{lead.mantissa * rho_n.mantissa, lead.exponent + rho_n.exponent};
  detail::normalize(lead_rho_n);
  ScaledTransferFunction<Scalar> out;
  out.rho = circle.rho;
  out.denominator = detail::normalized_coefficients(circle, den_samples, lead_rho_n);
  out.numerator = detail::normalized_coefficients(circle, num_samples, lead_rho_n);
  out.denominator.back() = Scalar(1);  // exactly monic
  return out;
}

// Coefficients of the pair's transfer function in s: those of transfer_function_scaled times rho^(n - k).
// Throws std::invalid_argument for inconsistent sizes, std::domain_error when det M_b = 0, and
// std::overflow_error when a coefficient exceeds the range of Scalar (double beyond roughly 150 coordinates of
// stiff machine structure: use long double, transfer_function_scaled, or the FRF from M, C, K).
template <typename Scalar>
TransferFunctionCoefficients<Scalar> transfer_function_coefficients(const TransferFunctionSystem<Scalar>& sys,
                                                                    const std::vector<int>& block) {
  using std::isfinite;
  using std::ldexp;
  const ScaledTransferFunction<Scalar> scaled = transfer_function_scaled(sys, block);
  const int n = static_cast<int>(scaled.denominator.size()) - 1;
  TransferFunctionCoefficients<Scalar> out;
  auto unscale = [&](const std::vector<Scalar>& c, std::vector<Scalar>& a) {
    for (int k = 0; k <= n; ++k) {
      const detail::Scaled<Scalar> r = detail::scaled_power(scaled.rho, n - k);
      const Scalar x = c[static_cast<std::size_t>(k)] * r.mantissa;
      const long e = std::max<long>(std::min<long>(r.exponent, 100000), -100000);
      a.push_back(ldexp(x, static_cast<int>(e)));
      if (!isfinite(a.back()))
        throw std::overflow_error("transfer_function_coefficients: coefficient " + std::to_string(k) + " of a " +
                                  std::to_string(block.size()) +
                                  "-coordinate block exceeds the range of this floating type; use long double, "
                                  "transfer_function_scaled (coefficients in s / rho) or the FRF");
    }
  };
  unscale(scaled.denominator, out.denominator);
  unscale(scaled.numerator, out.numerator);
  out.denominator.back() = Scalar(1);
  return out;
}

// Jacobian of the coefficients with respect to parameters, given d(sys)/d p_j for each parameter j.
template <typename Scalar>
TransferFunctionJacobian<Scalar> transfer_function_jacobian(
    const TransferFunctionSystem<Scalar>& sys, const std::vector<TransferFunctionSystem<Scalar>>& derivatives,
    const std::vector<int>& block) {
  using Complex = std::complex<Scalar>;
  const detail::BlockSystem<Scalar> bs = detail::restrict_to_block(sys, block);
  const int nb = static_cast<int>(block.size());
  const detail::CircleSampling<Scalar> circle(2 * nb + 1, detail::frequency_scale(bs.M, bs.K));
  const std::size_t N = circle.points.size();

  // det P, det Q, the LU of P and the solves x = P^-1 b, y^T = c P^-1 at every point, shared by all parameters.
  std::vector<Eigen::PartialPivLU<detail::ComplexMatrix<Scalar>>> lu_p;
  std::vector<Complex> det_p, neg_det_q;
  std::vector<detail::ComplexMatrix<Scalar>> x, y;
  for (const auto& s : circle.points) {
    lu_p.emplace_back(bs.P(s));
    det_p.push_back(lu_p.back().determinant());
    neg_det_q.push_back(-Eigen::PartialPivLU<detail::ComplexMatrix<Scalar>>(bs.Q(s)).determinant());
    const detail::ComplexMatrix<Scalar> q = bs.Q(s);
    x.push_back(lu_p.back().solve(q.topRightCorner(nb, 1)));
    y.push_back(lu_p.back().transpose().solve(q.bottomLeftCorner(1, nb).transpose()));
  }
  const std::vector<Scalar> den = circle.coefficients(det_p);
  const std::vector<Scalar> num = circle.coefficients(neg_det_q);
  const Scalar lead = bs.M.determinant();
  if (lead == Scalar(0)) throw std::domain_error("transfer_function_jacobian: singular mass matrix block");

  TransferFunctionJacobian<Scalar> out;
  for (const auto& d : derivatives) {
    const detail::BlockSystem<Scalar> db = detail::restrict_to_block(d, block);
    std::vector<Complex> dden_samples(N), dnum_samples(N);
    for (std::size_t j = 0; j < N; ++j) {
      const Complex s = circle.points[j];
      // D = det P:      dD = D trace(P^-1 dP).
      // N = D c P^-1 b: dN = dD g + D (dc x + y^T db - y^T dP x),  g = c x.
      // Only P is inverted: it is regular on the circle unless a pole lies exactly on it, whereas Q is
      // singular wherever N vanishes (e.g. a pair with a zero numerator).
      const detail::ComplexMatrix<Scalar> dP = db.P(s), dQ = db.Q(s);
      const Complex dD = det_p[j] * lu_p[j].solve(dP).trace();
      const Complex g = (bs.Q(s).bottomLeftCorner(1, nb) * x[j])(0, 0);
      const Complex inner = (dQ.bottomLeftCorner(1, nb) * x[j])(0, 0) +
                            (y[j].transpose() * dQ.topRightCorner(nb, 1))(0, 0) -
                            (y[j].transpose() * dP * x[j])(0, 0);
      dden_samples[j] = dD;
      dnum_samples[j] = dD * g + det_p[j] * inner;
    }
    const std::vector<Scalar> dden = circle.coefficients(dden_samples);
    const std::vector<Scalar> dnum = circle.coefficients(dnum_samples);
    const Scalar dlead = lead * bs.M.partialPivLu().solve(db.M).trace();  // d det M_b, exactly
    std::vector<Scalar> jn(N), jd(N);
    // (x / lead)' = (x' lead - x lead') / lead^2
    for (std::size_t k = 0; k < N; ++k) {
      jn[k] = (dnum[k] * lead - num[k] * dlead) / (lead * lead);
      jd[k] = (dden[k] * lead - den[k] * dlead) / (lead * lead);
    }
    jd.back() = Scalar(0);
    using std::isfinite;
    for (std::size_t k = 0; k < N; ++k)
      if (!isfinite(jn[k]) || !isfinite(jd[k]))
        throw std::overflow_error("transfer_function_jacobian: the coefficients' derivatives of a " +
                                  std::to_string(block.size()) +
                                  "-coordinate block exceed the range of this floating type; use long double or "
                                  "the FRF's Jacobian");
    out.numerator.push_back(std::move(jn));
    out.denominator.push_back(std::move(jd));
  }
  return out;
}

// Compiled once, in the runtime library (src/dynamics/transfer_function.cpp), for double and long double: generated
// code calls these for every run-time pair, and instantiating Eigen's complex LU for both types in each generated
// translation unit took most of its compile time (18 of 28 s of CPU for the spindle). Other Scalar types (e.g.
// mpfr::mpreal) are instantiated from the definitions above where they are used.
#define MBGEN_TRANSFER_FUNCTION_INSTANTIATIONS(EXTERN, Scalar)                                                    \
  EXTERN template ScaledTransferFunction<Scalar> transfer_function_scaled<Scalar>(                              \
      const TransferFunctionSystem<Scalar>&, const std::vector<int>&);                                          \
  EXTERN template TransferFunctionCoefficients<Scalar> transfer_function_coefficients<Scalar>(                  \
      const TransferFunctionSystem<Scalar>&, const std::vector<int>&);                                          \
  EXTERN template TransferFunctionJacobian<Scalar> transfer_function_jacobian<Scalar>(                          \
      const TransferFunctionSystem<Scalar>&, const std::vector<TransferFunctionSystem<Scalar>>&,                \
      const std::vector<int>&);
#ifndef MBGEN_TRANSFER_FUNCTION_INSTANTIATE
MBGEN_TRANSFER_FUNCTION_INSTANTIATIONS(extern, double)
MBGEN_TRANSFER_FUNCTION_INSTANTIATIONS(extern, long double)
#endif

}  // namespace mbgen
