#include "armax.hpp"

#include "lag_polynomials.hpp"
#include "polynomial.hpp"
#include "mbgen/dynamics/parallel.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen::methods {

namespace {

using Complex = std::complex<double>;

double rms(const Eigen::VectorXd& v) {
  const double r = std::sqrt(v.squaredNorm() / double(std::max<Eigen::Index>(v.size(), 1)));
  return r > 0 ? r : 1.0;
}

// The coefficient vector theta = [a_1..a_n | b_0,l0..b_0,n | ... | b_O-1,l0..n | c_1..c_n] on normalised signals.
// The search itself moves A and C in second-order sections (below); theta is what the starts and the result use.
struct Layout {
  int n = 0, first_lag = 1, outputs = 0;
  int nb() const { return n - first_lag + 1; }
  Eigen::Index a(int l) const { return l - 1; }
  Eigen::Index b(int o, int l) const { return n + Eigen::Index(o) * nb() + (l - first_lag); }
  Eigen::Index c(int l) const { return n + Eigen::Index(outputs) * nb() + l - 1; }
  Eigen::Index size() const { return 2 * Eigen::Index(n) + Eigen::Index(outputs) * nb(); }
};

struct Signals {
  Eigen::VectorXd u;               // input / RMS
  std::vector<Eigen::VectorXd> y;  // outputs / RMS
};

// ---- the search coordinates: phi = [A's sections | b (as in theta) | C's sections] ----

Eigen::VectorXd to_search(const Layout& L, const Eigen::VectorXd& theta) {
  Eigen::VectorXd phi = theta;
  phi.head(L.n) = sections_of(theta.head(L.n));
  phi.segment(L.c(1), L.n) = sections_of(theta.segment(L.c(1), L.n));
  return phi;
}

Eigen::VectorXd to_coefficients(const Layout& L, const Eigen::VectorXd& phi) {
  const Sections S{L.n};
  Eigen::VectorXd theta = phi;
  theta.head(L.n) = polynomial_of(S, phi.head(L.n));
  theta.segment(L.c(1), L.n) = polynomial_of(S, phi.segment(L.c(1), L.n));
  return theta;
}

// d theta / d phi: the sections' products' derivatives (b is the identity).
Eigen::MatrixXd coefficient_jacobian(const Layout& L, const Eigen::VectorXd& phi) {
  const Sections S{L.n};
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(L.size(), L.size());
  for (const Eigen::Index base : {Eigen::Index(0), L.c(1)}) {
    const Eigen::VectorXd v = phi.segment(base, L.n);
    T.block(base, base, L.n, L.n).setZero();
    for (int k = 0; k < S.count(); ++k) {
      const Eigen::VectorXd others = polynomial_of(S, v, k);
      for (int l = 1; l <= S.order(k); ++l) {
        // d/ds_l of (1 + ... + s_l q^-l ...) * others = q^-l * (1 + others)
        const Eigen::Index col = base + S.offset(k) + l - 1;
        T(base + l - 1, col) += 1;
        for (Eigen::Index m = 0; m < others.size() && l + m < L.n; ++m) T(base + l + m, col) += others[m];
      }
    }
  }
  return T;
}

// The prediction errors e_o = (A y_o - B_o u) / C at search point phi; returns sum_o |e_o|^2.
double prediction_errors(const Layout& L, const Signals& s, const Eigen::VectorXd& phi, std::vector<Eigen::VectorXd>& e) {
  const Eigen::Index N = s.u.size();
  const Sections S{L.n};
  const Eigen::VectorXd a = polynomial_of(S, phi.head(L.n)), c = polynomial_of(S, phi.segment(L.c(1), L.n));
  e.resize(s.y.size());
  double cost = 0;
  for (int o = 0; o < L.outputs; ++o) {
    Eigen::VectorXd& x = e[static_cast<std::size_t>(o)];
    x = multiply_by(a, s.y[static_cast<std::size_t>(o)]);
    for (int l = L.first_lag; l <= L.n; ++l) x.tail(N - l) -= phi[L.b(o, l)] * s.u.head(N - l);
    divide_by(c, x);
    cost += x.squaredNorm();
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

// What every output's prediction-error derivatives share: C's polynomial, u / C, and A without each of its sections.
struct DerivativeParts {
  Sections S;
  Eigen::VectorXd cv, c, uf;
  std::vector<Eigen::VectorXd> a_without;
  DerivativeParts(const Layout& L, const Signals& s, const Eigen::VectorXd& phi)
      : S{L.n}, cv(phi.segment(L.c(1), L.n)), c(polynomial_of(S, cv)), uf(s.u) {
    divide_by(c, uf);
    const Eigen::VectorXd av = phi.head(L.n);
    a_without.resize(static_cast<std::size_t>(S.count()));
    for (int k = 0; k < S.count(); ++k) a_without[static_cast<std::size_t>(k)] = polynomial_of(S, av, k);
  }
};

// Output o's prediction errors' derivatives (N x 2 n + nb: A's sections, o's b, C's sections), for A's section k
// d e_o / d s_l = q^-l (A / A_k) y_o / C; for b, -q^-l u / C; for C's section k, -q^-l e_o / C_k (from
// C e = A y - B u). J is N rows, zero on entry; `global` gets each column's index in phi.
void output_derivatives(const Layout& L, const Signals& s, const DerivativeParts& d, const Eigen::VectorXd& e_o, int o,
                        Eigen::MatrixXd& J, std::vector<Eigen::Index>& global) {
  const Eigen::Index N = s.u.size();
  const Sections& S = d.S;
  const Eigen::VectorXd& y = s.y[static_cast<std::size_t>(o)];
  for (int k = 0; k < S.count(); ++k) {
    Eigen::VectorXd w = multiply_by(d.a_without[static_cast<std::size_t>(k)], y);
    divide_by(d.c, w);
    Eigen::VectorXd v = e_o;
    divide_by(section(S, d.cv, k), v);
    for (int l = 1; l <= S.order(k); ++l) {
      J.col(S.offset(k) + l - 1).tail(N - l) = w.head(N - l);
      J.col(L.n + L.nb() + S.offset(k) + l - 1).tail(N - l) = -v.head(N - l);
    }
  }
  global.resize(static_cast<std::size_t>(2 * Eigen::Index(L.n) + L.nb()));
  for (Eigen::Index j = 0; j < L.n; ++j) {
    global[static_cast<std::size_t>(j)] = j;
    global[static_cast<std::size_t>(L.n + L.nb() + j)] = L.c(1) + j;
  }
  for (int l = L.first_lag; l <= L.n; ++l) {
    J.col(L.n + l - L.first_lag).tail(N - l) = -d.uf.head(N - l);
    global[static_cast<std::size_t>(L.n + l - L.first_lag)] = L.b(o, l);
  }
}

// The prediction errors' derivatives with respect to phi, stacked output by output (rows o N .. o N + N - 1).
Eigen::MatrixXd jacobian(const Layout& L, const Signals& s, const Eigen::VectorXd& phi,
                         const std::vector<Eigen::VectorXd>& e) {
  const Eigen::Index N = s.u.size();
  const DerivativeParts d(L, s, phi);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(N * L.outputs, L.size());
  Eigen::MatrixXd block(N, 2 * Eigen::Index(L.n) + L.nb());
  std::vector<Eigen::Index> global;
  for (int o = 0; o < L.outputs; ++o) {
    block.setZero();
    output_derivatives(L, s, d, e[static_cast<std::size_t>(o)], o, block, global);
    for (Eigen::Index i = 0; i < block.cols(); ++i)
      J.col(global[static_cast<std::size_t>(i)]).segment(Eigen::Index(o) * N, N) = block.col(i);
  }
  return J;
}

// J^T J and J^T e of the Jacobian above, accumulated output by output on the columns each touches (A's and C's
// sections, its own b): a third of the work of the full product for three outputs.
void normal_equations(const Layout& L, const Signals& s, const Eigen::VectorXd& phi,
                      const std::vector<Eigen::VectorXd>& e, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
  const Eigen::Index N = s.u.size(), p = L.size();
  const DerivativeParts d(L, s, phi);
  const Eigen::Index local = 2 * Eigen::Index(L.n) + L.nb();
  std::vector<Eigen::Index> global;
  H = Eigen::MatrixXd::Zero(p, p);
  g = Eigen::VectorXd::Zero(p);
  Eigen::MatrixXd J(N, local);
  for (int o = 0; o < L.outputs; ++o) {
    J.setZero();
    output_derivatives(L, s, d, e[static_cast<std::size_t>(o)], o, J, global);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(local, local);
    G.selfadjointView<Eigen::Lower>().rankUpdate(J.transpose());
    G = G.selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd gl = J.transpose() * e[static_cast<std::size_t>(o)];
    for (Eigen::Index i = 0; i < local; ++i) {
      g[global[static_cast<std::size_t>(i)]] += gl[i];
      for (Eigen::Index j = 0; j < local; ++j)
        H(global[static_cast<std::size_t>(i)], global[static_cast<std::size_t>(j)]) += G(i, j);
    }
  }
}

int reflect_c(const Layout& L, Eigen::VectorXd& phi) {
  Eigen::VectorXd v = phi.segment(L.c(1), L.n);
  const int r = reflect(Sections{L.n}, v);
  phi.segment(L.c(1), L.n) = v;
  return r;
}

struct Search {
  Eigen::VectorXd phi;
  double cost = std::numeric_limits<double>::infinity();
  double lambda = 1e-4;
  int iterations = 0, reflections = 0;
  bool converged = false;
};

// Levenberg-Marquardt (Marquardt's diagonal scaling) on the prediction errors in the search coordinates, C's
// sections reflected into the unit circle after every step; a step is taken only when it lowers the cost.
// Converged when no step lowers the cost or kPatience steps in a row each raise the log-likelihood by less than
// kLikelihood: the estimate is then within a fraction of its std of the optimum in every direction that matters. (An
// order above what the data show has a pole-zero pair, A's, B's and C's common factor, free to drift, along which
// the cost fell by a few millionths per step for a hundred steps without changing the transfer function; where C's
// roots press against the unit circle the gains come irregularly, a small one between larger ones.)
// `previous` continues an earlier search.
constexpr double kLikelihood = 0.1;
constexpr int kPatience = 3;
constexpr int kTrialIterations = 8;
Search minimise(const Layout& L, const Signals& s, Eigen::VectorXd phi, int max_iterations,
                const Search* previous = nullptr) {
  Search out;
  if (previous) {
    out.iterations = previous->iterations;
    out.reflections = previous->reflections;
  }
  out.reflections += reflect_c(L, phi);
  std::vector<Eigen::VectorXd> e, et;
  double cost = prediction_errors(L, s, phi, e);
  if (!std::isfinite(cost)) {
    out.phi = phi;
    return out;
  }
  double lambda = previous ? previous->lambda : 1e-4;
  int small_gains = 0;
  for (int it = 0; it < max_iterations; ++it) {
    // The step minimises |J step + e|^2 + lambda |D step|^2 (D the column norms: Marquardt's scaling), from the
    // normal equations scaled to unit diagonal (in the sections' coordinates J is well conditioned).
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    normal_equations(L, s, phi, e, H, g);
    const Eigen::VectorXd d = H.diagonal().cwiseMax(1e-300).cwiseSqrt();
    const Eigen::MatrixXd Hs = d.cwiseInverse().asDiagonal() * H * d.cwiseInverse().asDiagonal();
    const Eigen::VectorXd gs = g.cwiseQuotient(d);
    bool accepted = false;
    double cost_trial = cost;
    Eigen::VectorXd trial;
    int reflected = 0;
    while (lambda < 1e12) {
      Eigen::MatrixXd K = Hs;
      K.diagonal().array() += lambda;
      const Eigen::LLT<Eigen::MatrixXd> llt(K);
      if (llt.info() == Eigen::Success) {
        const Eigen::VectorXd step = -llt.solve(gs).cwiseQuotient(d);
        if (step.allFinite()) {
          trial = phi + step;
          reflected = reflect_c(L, trial);
          cost_trial = prediction_errors(L, s, trial, et);
          if (cost_trial < cost) {
            accepted = true;
            break;
          }
        }
      }
      lambda *= 10;
    }
    ++out.iterations;
    if (!accepted) {  // no step lowers the cost: a minimum, to rounding
      out.converged = true;
      break;
    }
    // The step's gain in log-likelihood, N/2 ln(cost before / cost after) (N the prediction errors).
    const double gain = 0.5 * double(s.u.size()) * L.outputs * std::log(cost / cost_trial);
    phi = trial;
    e.swap(et);
    cost = cost_trial;
    out.reflections += reflected;
    lambda = std::max(lambda / 10, 1e-12);
    small_gains = gain < kLikelihood ? small_gains + 1 : 0;
    if (small_gains == kPatience) {
      out.converged = true;
      break;
    }
  }
  out.phi = phi;
  out.cost = cost;
  out.lambda = lambda;
  return out;
}

// Least squares of y_o(k) on -y_o(k-l) (l = 1..n), u(k-l) (l = l0..n) and, with `innovations`, their lags
// e_o(k-l) (l = 1..n; coefficients c_l): one stacked system over all outputs and samples, zero pre-sample values.
// Returns theta in the layout of order n (c zero without innovations).
Eigen::VectorXd regression(const Layout& L, const Signals& s, const std::vector<Eigen::VectorXd>* innovations) {
  const Eigen::Index N = s.u.size();
  const int n = L.n;
  const Eigen::Index p = innovations ? L.size() : L.size() - n;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(N * L.outputs, p);
  Eigen::VectorXd t(N * L.outputs);
  for (int o = 0; o < L.outputs; ++o) {
    const Eigen::Index r0 = Eigen::Index(o) * N;
    const Eigen::VectorXd& y = s.y[static_cast<std::size_t>(o)];
    t.segment(r0, N) = y;
    for (int l = 1; l <= n; ++l) X.col(L.a(l)).segment(r0 + l, N - l) = -y.head(N - l);
    for (int l = L.first_lag; l <= n; ++l) X.col(L.b(o, l)).segment(r0 + l, N - l) = s.u.head(N - l);
    if (innovations)
      for (int l = 1; l <= n; ++l)
        X.col(L.c(l)).segment(r0 + l, N - l) = (*innovations)[static_cast<std::size_t>(o)].head(N - l);
  }
  const Eigen::VectorXd sol = X.colPivHouseholderQr().solve(t);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(L.size());
  theta.head(p) = sol;
  return theta;
}

// The output-error start: A from given discrete poles (padded with zero lags to order n), each B_o by least squares
// of y_o on the lags of u / A (the output error is linear in B at fixed A), and C = A (white output noise).
Eigen::VectorXd output_error_start(const Layout& L, const Signals& s, const std::vector<Complex>& z) {
  std::vector<Complex> roots;
  for (const Complex& r : z) {
    roots.push_back(r);
    roots.push_back(std::conj(r));
  }
  const Eigen::VectorXd A = poly_from_roots(roots).real();  // ascending in z, A[m] = 1
  const int m = static_cast<int>(roots.size());
  Eigen::VectorXd a = Eigen::VectorXd::Zero(L.n);
  for (int l = 1; l <= std::min(m, L.n); ++l) a[l - 1] = A[m - l];
  Eigen::VectorXd uf = s.u;
  divide_by(a, uf);
  const Eigen::Index N = s.u.size();
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(N, L.nb());
  for (int l = L.first_lag; l <= L.n; ++l) X.col(l - L.first_lag).tail(N - l) = uf.head(N - l);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(L.size());
  theta.head(L.n) = a;
  theta.segment(L.c(1), L.n) = a;
  for (int o = 0; o < L.outputs; ++o) {
    const Eigen::VectorXd b = qr.solve(s.y[static_cast<std::size_t>(o)]);
    for (int l = L.first_lag; l <= L.n; ++l) theta[L.b(o, l)] = b[l - L.first_lag];
  }
  return theta;
}

}  // namespace

Eigen::VectorXd ArmaxEstimate::a_polynomial() const {
  Eigen::VectorXd A = Eigen::VectorXd::Zero(order + 1);
  A[order] = 1;
  for (int l = 1; l <= order; ++l) A[order - l] = a[l - 1];
  return A;
}

Eigen::VectorXd ArmaxEstimate::b_polynomial(std::size_t output) const {
  Eigen::VectorXd B = Eigen::VectorXd::Zero(order + 1);
  for (int l = first_lag; l <= order; ++l) B[order - l] = b[output][l - first_lag];
  return B;
}

Eigen::VectorXd ArmaxEstimate::c_polynomial() const {
  Eigen::VectorXd C = Eigen::VectorXd::Zero(order + 1);
  C[order] = 1;
  for (int l = 1; l <= order; ++l) C[order - l] = c[l - 1];
  return C;
}

ArmaxEstimate estimate_armax(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y, int n,
                             bool first_order_hold, const ArmaxOptions& options, const ArmaxEstimate* previous,
                             const std::vector<std::complex<double>>& poles, double dt) {
  // A caller's bug: std::logic_error, not invalid_argument, which the callers take for data that cannot serve.
  if (y.empty() || n < 1) throw std::logic_error("estimate_armax: bad arguments");
  Layout L;
  L.n = n;
  L.first_lag = first_order_hold ? 0 : 1;
  L.outputs = static_cast<int>(y.size());
  const double su = rms(u);
  Signals s;
  s.u = u / su;
  std::vector<double> sy;
  for (const Eigen::VectorXd& v : y) {
    sy.push_back(rms(v));
    s.y.push_back(v / sy.back());
  }
  const Eigen::Index N = u.size();

  // The starts (names for method_details).
  std::vector<std::pair<std::string, Eigen::VectorXd>> starts;
  const Eigen::VectorXd arx = regression(L, s, nullptr);
  starts.emplace_back("arx (C = 1)", arx);
  if (!poles.empty()) {
    std::vector<Complex> z;
    for (const Complex& l : poles) z.push_back(std::exp(l * dt));
    if (2 * static_cast<int>(z.size()) <= n) starts.emplace_back("long arx's poles (C = A)", output_error_start(L, s, z));
  }
  {
    // Hannan-Rissanen: a long ARX's residuals as the innovations.
    Layout H = L;
    H.n = std::max(options.long_arx_order, 2 * n);
    while (H.n > n && double(N) * L.outputs < 20.0 * double(H.size() - H.n)) --H.n;
    const Eigen::VectorXd t = regression(H, s, nullptr);
    std::vector<Eigen::VectorXd> innovations;
    Eigen::VectorXd long_theta = t;
    long_theta.segment(H.c(1), H.n).setZero();
    prediction_errors(H, s, to_search(H, long_theta), innovations);
    starts.emplace_back("hannan-rissanen", regression(L, s, &innovations));
  }
  if (previous && previous->order == n - 1 && previous->first_lag == L.first_lag &&
      previous->b.size() == y.size()) {
    Eigen::VectorXd t = Eigen::VectorXd::Zero(L.size());
    for (int l = 1; l < n; ++l) {
      t[L.a(l)] = previous->a[l - 1];
      t[L.c(l)] = previous->c[l - 1];
    }
    for (int o = 0; o < L.outputs; ++o)
      for (int l = L.first_lag; l < n; ++l)
        t[L.b(o, l)] = previous->b[static_cast<std::size_t>(o)][l - L.first_lag] * su / sy[static_cast<std::size_t>(o)];
    starts.emplace_back("order " + std::to_string(n - 1) + " optimum", t);
  }

  ArmaxEstimate out;
  out.order = n;
  out.first_lag = L.first_lag;
  // Every start for a few iterations, the best of them on to convergence (a search that has not settled in the
  // first iterations rarely overtakes, and the full searches are what costs).
  std::vector<Search> trials(starts.size());
  parallel_for(starts.size(), options.threads, [&](std::size_t i) {
    trials[i] = minimise(L, s, to_search(L, starts[i].second), std::min(kTrialIterations, options.max_iterations));
  });
  Search best;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    out.start_costs.emplace_back(starts[i].first, trials[i].cost);
    if (trials[i].cost < best.cost) {
      best = trials[i];
      out.start = starts[i].first;
    }
  }
  if (!best.converged && std::isfinite(best.cost))
    best = minimise(L, s, best.phi, options.max_iterations - best.iterations, &best);
  if (!std::isfinite(best.cost))
    throw std::invalid_argument("ARMAX of order " + std::to_string(n) + ": no start gives finite prediction errors");
  const Eigen::VectorXd theta = to_coefficients(L, best.phi);
  out.cost = best.cost;
  out.iterations = best.iterations;
  out.converged = best.converged;
  out.reflections = best.reflections;
  out.parameters = L.size();
  const double Nt = double(N) * L.outputs, p = double(out.parameters);
  out.aic = Nt * std::log(out.cost / Nt) + 2 * p;
  out.bic = Nt * std::log(out.cost / Nt) + p * std::log(Nt);
  out.fpe = out.cost / Nt * (Nt + p) / (Nt - p);

  // Physical units: b scaled back; a and c are dimensionless.
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(L.size());
  out.a = theta.head(n);
  out.c = theta.segment(L.c(1), n);
  for (int o = 0; o < L.outputs; ++o) {
    Eigen::VectorXd b(L.nb());
    for (int l = L.first_lag; l <= n; ++l) {
      scale[L.b(o, l)] = sy[static_cast<std::size_t>(o)] / su;
      b[l - L.first_lag] = theta[L.b(o, l)] * scale[L.b(o, l)];
    }
    out.b.push_back(b);
  }
  out.largest_c_root = largest_root(out.c);
  // Covariance s^2 (J^T J)^-1 in the search coordinates (a pseudo-inverse: an over-parameterised order has a common
  // factor, a null direction), mapped to the coefficients by d theta / d phi.
  std::vector<Eigen::VectorXd> e;
  prediction_errors(L, s, best.phi, e);
  const Eigen::MatrixXd J = jacobian(L, s, best.phi, e);
  const Eigen::VectorXd d = J.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J * d.cwiseInverse().asDiagonal(), Eigen::ComputeThinV);
  Eigen::VectorXd inv = svd.singularValues();
  for (Eigen::Index i = 0; i < inv.size(); ++i)
    inv[i] = inv[i] > svd.singularValues()[0] * 1e-10 ? 1 / (inv[i] * inv[i]) : 0;
  const Eigen::MatrixXd Hi =
      d.cwiseInverse().asDiagonal() * (svd.matrixV() * inv.asDiagonal() * svd.matrixV().transpose()) *
      d.cwiseInverse().asDiagonal();
  const double s2 = out.cost / std::max(Nt - p, 1.0);
  const Eigen::MatrixXd T = coefficient_jacobian(L, best.phi);
  out.covariance = scale.asDiagonal() * (T * (s2 * Hi) * T.transpose()) * scale.asDiagonal();
  out.a_sections = best.phi.head(n);
  out.a_section_covariance = s2 * Hi.topLeftCorner(n, n);
  return out;
}

ArmaxIdentification identify_armax(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y,
                                   const std::vector<std::string>& outputs, const std::string& input, double dt,
                                   bool first_order_hold, int q, const std::vector<int>& numerator_degree,
                                   const ArmaxOptions& options, const ArxOptions& pruning) {
  const int O = static_cast<int>(y.size());
  const Eigen::Index N = u.size();
  if (O == 0 || q < 2 || q % 2 || static_cast<int>(numerator_degree.size()) != O)
    throw std::logic_error("identify_armax: bad arguments");  // a caller's bug (estimate_armax), not the data's
  const int first_lag = first_order_hold ? 0 : 1;
  auto coefficients = [&](int n) { return 2.0 * n + double(O) * (n - first_lag + 1); };
  if (double(O) * double(N) < 20.0 * coefficients(q))
    throw std::invalid_argument("the record's " + std::to_string(N) + " samples are too few for an ARMAX model of order " +
                                std::to_string(q) + " (at least 20 prediction errors per coefficient)");
  int n_max = q + std::max(options.extra_orders, 0);
  while (n_max > q && double(O) * double(N) < 20.0 * coefficients(n_max)) --n_max;

  // The long ARX's kept poles (arx.hpp): the output-error start.
  std::vector<Complex> arx_poles;
  try {
    ArxOptions long_arx = pruning;
    long_arx.criterion = options.criterion;
    const ArxIdentification a = identify_arx(u, y, outputs, input, dt, first_order_hold, q, numerator_degree, long_arx);
    for (const ArxPole& p : a.poles)
      if (p.kept) arx_poles.push_back(p.lambda);
  } catch (const std::invalid_argument&) {
    // too short for the long ARX, or no mode kept: the other starts remain
  }

  ArmaxIdentification out;
  out.id.model = "ARMAX";
  out.id.samples = static_cast<long>(N);
  double best = std::numeric_limits<double>::infinity();
  for (int n = q; n <= n_max; ++n) {
    out.estimates.push_back(
        estimate_armax(u, y, n, first_order_hold, options, out.estimates.empty() ? nullptr : &out.estimates.back(),
                       arx_poles, dt));
    const ArmaxEstimate& e = out.estimates.back();
    ArxOrder row;
    row.order = n;
    row.parameters = e.parameters;
    row.rss = e.cost;
    row.aic = e.aic;
    row.bic = e.bic;
    row.fpe = e.fpe;
    out.id.orders.push_back(row);
    const double c = options.criterion == "bic" ? e.bic : options.criterion == "fpe" ? e.fpe : e.aic;
    if (c < best) {
      best = c;
      out.selected = static_cast<int>(out.estimates.size()) - 1;
    }
  }
  const ArmaxEstimate& chosen = out.estimates[static_cast<std::size_t>(out.selected)];
  out.id.selected_order = chosen.order;
  std::vector<Eigen::VectorXd> B;
  for (int o = 0; o < O; ++o) B.push_back(chosen.b_polynomial(static_cast<std::size_t>(o)));
  // The kept poles' covariance from the sections': each kept pole is the root z of its section z^2 + s_1 z + s_2
  // (dz/ds_1 = -z / (2z + s_1), dz/ds_2 = -1 / (2z + s_1)), lambda = ln z / dt.
  const PoleCovariance pole_covariance = [&](const std::vector<Complex>& kept) {
    const Sections S{chosen.order};
    const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(2 * m, chosen.order);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Complex z = std::exp(kept[static_cast<std::size_t>(k)] * dt);
      int best = -1;
      double distance = std::numeric_limits<double>::infinity();
      Complex root;
      for (int j = 0; j < S.count(); ++j) {
        if (S.order(j) != 2) continue;
        const double s1 = chosen.a_sections[S.offset(j)], s2 = chosen.a_sections[S.offset(j) + 1];
        const Complex r = (-s1 + std::sqrt(Complex(s1 * s1 - 4 * s2))) / 2.0;
        for (const Complex& c : {r, std::conj(r), Complex(-s1 - r)})
          if (std::abs(c - z) < distance) distance = std::abs(c - z), best = j, root = c;
      }
      if (best < 0) return Eigen::MatrixXd(Eigen::MatrixXd::Constant(2 * m, 2 * m, std::numeric_limits<double>::quiet_NaN()));
      const double s1 = chosen.a_sections[S.offset(best)];
      const Complex dz1 = -root / (2.0 * root + s1), dz2 = -1.0 / (2.0 * root + s1);
      const Complex to_lambda = 1.0 / (root * dt);
      const Complex d1 = dz1 * to_lambda, d2 = dz2 * to_lambda;
      G(2 * k, S.offset(best)) = d1.real();
      G(2 * k + 1, S.offset(best)) = d1.imag();
      G(2 * k, S.offset(best) + 1) = d2.real();
      G(2 * k + 1, S.offset(best) + 1) = d2.imag();
    }
    return Eigen::MatrixXd(G * chosen.a_section_covariance * G.transpose());
  };
  prune_and_fit_residues(chosen.a_polynomial(), B, u, y, outputs, input, dt, first_order_hold, q, numerator_degree,
                         pruning, out.id, pole_covariance);
  out.id.tf.covariance_note =
      "linearised: the kept poles' covariance from the ARMAX coefficients' through the residue fit, plus the "
      "residues' given the poles";
  return out;
}

}  // namespace mbgen::methods
