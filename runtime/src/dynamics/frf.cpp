#include "mbgen/dynamics/frf.hpp"

#include "model_checks.hpp"
#include "band_lu.hpp"
#include "small_lu.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mbgen {
namespace {

using cd = std::complex<double>;
using numerics::kTwoPi;

// Buffers for one FRF evaluation, reused at every frequency. P is factored dense, or in band storage when M, C
// and K together are banded narrowly enough to pay (band_lu.hpp: a chain of bodies; models of 32 coordinates or
// more only).
struct Workspace {
  detail::SmallLu lu;
  detail::BandLu band_lu;
  bool banded = false;
  Eigen::MatrixXcd B, Cout, X, Yt, H, J;
  Eigen::Index n = 0, inputs = 0, outputs = 0;

  explicit Workspace(const ModelMatrices& m)
      : B(m.B.cast<cd>()), n(m.M.rows()), inputs(m.B.cols()), outputs(m.Cd.rows()) {
    const detail::Bandwidth band = detail::bandwidth_of({&m.M, &m.C, &m.K});
    banded = detail::band_pays(n, band);
    if (banded)
      band_lu.resize(n, band);
    else
      lu.resize(n);
    Cout.resize(outputs, n);
    X.resize(n, inputs);
    Yt.resize(n, outputs);
    H.resize(outputs, inputs);
  }

  // P(jw) = K - w^2 M + jw C, factorised (dense: in `target` when given, else in `lu`); throws if singular to
  // working precision.
  void factor(const ModelMatrices& m, double f_hz, const char* where, detail::SmallLu* target = nullptr) {
    const double w = kTwoPi * f_hz, w2 = w * w;
    double ratio = 0;
    detail::SmallLu& lu = target ? *target : this->lu;
    if (banded) {
      const detail::Bandwidth& b = band_lu.band();
      for (Eigen::Index c = 0; c < n; ++c)
        for (Eigen::Index r = std::max<Eigen::Index>(0, c - b.upper); r <= std::min(n - 1, c + b.lower); ++r)
          band_lu.at(r, c) = cd(m.K(r, c) - w2 * m.M(r, c), w * m.C(r, c));
      ratio = band_lu.factor();
    } else {
      Eigen::MatrixXcd& P = lu.matrix();
      for (Eigen::Index c = 0; c < n; ++c)
        for (Eigen::Index r = 0; r < n; ++r) P(r, c) = cd(m.K(r, c) - w2 * m.M(r, c), w * m.C(r, c));
      ratio = lu.factor();
    }
    if (!(ratio > static_cast<double>(n) * std::numeric_limits<double>::epsilon())) {
      std::ostringstream msg;
      msg << where << ": dynamic stiffness K - w^2 M + jw C is singular at " << f_hz
          << " Hz (an undamped resonance, or a rigid-body mode at 0 Hz)";
      throw DynamicsError(msg.str());
    }
  }

  // Cout = Cd + s Cv + s^2 Ca at s = jw.
  void output_matrix(const ModelMatrices& m, double w) {
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = 0; r < outputs; ++r) Cout(r, c) = cd(m.Cd(r, c) - w * w * m.Ca(r, c), w * m.Cv(r, c));
  }

  void solve(Eigen::MatrixXcd& x) const { banded ? band_lu.solve(x) : lu.solve(x); }
  void solve_transposed(Eigen::MatrixXcd& x) const { banded ? band_lu.solve_transposed(x) : lu.solve_transposed(x); }

  // X = P^-1 B, H = Cout X; with the dense factors `factors` when given (a cache's), else the workspace's.
  void response(const detail::SmallLu* factors = nullptr) {
    X = B;
    if (factors)
      factors->solve(X);
    else
      solve(X);
    H.noalias() = Cout * X;
  }
};

void check_frequencies(const std::vector<double>& freqs_hz, const char* where) {
  for (std::size_t k = 0; k < freqs_hz.size(); ++k)
    if (!std::isfinite(freqs_hz[k])) {
      std::ostringstream msg;
      msg << where << ": frequency " << k << " is not finite";
      throw DynamicsError(msg.str());
    }
}

bool same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

bool same(const ModelMatrices& a, const ModelMatrices& b) {
  return same(a.M, b.M) && same(a.C, b.C) && same(a.K, b.K) && same(a.B, b.B) && same(a.Cd, b.Cd) &&
         same(a.Cv, b.Cv) && same(a.Ca, b.Ca);
}

// A matrix's derivative entries ordered by (parameter, row), and the ranges of entries that share both.
struct EntryGroup {
  int param = 0, row = 0;
  std::size_t first = 0, last = 0;
};

struct GroupedEntries {
  std::vector<DerivativeEntry> entries;
  std::vector<EntryGroup> groups;

  explicit GroupedEntries(const std::vector<DerivativeEntry>& unordered) : entries(unordered) {
    std::stable_sort(entries.begin(), entries.end(), [](const DerivativeEntry& a, const DerivativeEntry& b) {
      return a.param != b.param ? a.param < b.param : a.row < b.row;
    });
    for (std::size_t e = 0; e < entries.size(); ++e)
      if (groups.empty() || groups.back().param != entries[e].param || groups.back().row != entries[e].row)
        groups.push_back({entries[e].param, entries[e].row, e, e + 1});
      else
        groups.back().last = e + 1;
  }
};

// The factors kept at most (complex entries of P over all lines: 4 MiB), so a large model on many lines is not
// copied around for a small gain.
constexpr double kCachedEntries = 262144;

}  // namespace

struct FrfFactorCache::Impl {
  bool valid = false;
  ModelMatrices m;            // filled with these matrices ...
  std::vector<double> freqs;  // ... at these frequencies
  std::vector<detail::SmallLu> lu;
  std::vector<Eigen::MatrixXcd> X;

  bool holds(const ModelMatrices& other, const std::vector<double>& f) const {
    return valid && freqs == f && same(m, other);
  }
};

FrfFactorCache::FrfFactorCache() : impl_(std::make_unique<Impl>()) {}
FrfFactorCache::~FrfFactorCache() = default;
FrfFactorCache::FrfFactorCache(FrfFactorCache&&) noexcept = default;
FrfFactorCache& FrfFactorCache::operator=(FrfFactorCache&&) noexcept = default;

FrfWork frf(const ModelMatrices& m, const std::vector<double>& freqs_hz, const FrfSink& sink, FrfFactorCache* keep) {
  const char* where = "frf";
  detail::check_matrices(m, where);
  check_frequencies(freqs_hz, where);
  Workspace ws(m);
  const double entries = static_cast<double>(ws.n) * static_cast<double>(ws.n) * static_cast<double>(freqs_hz.size());
  FrfFactorCache::Impl* cache = keep && !ws.banded && entries <= kCachedEntries ? &keep->impl() : nullptr;
  if (keep) keep->impl().valid = false;
  if (cache) {
    cache->m = m;
    cache->freqs = freqs_hz;
    cache->lu.resize(freqs_hz.size());
    cache->X.resize(freqs_hz.size());
  }
  FrfWork work;
  for (std::size_t k = 0; k < freqs_hz.size(); ++k) {
    detail::SmallLu* target = nullptr;
    if (cache) {
      target = &cache->lu[k];
      target->resize(ws.n);
    }
    ws.factor(m, freqs_hz[k], where, target);
    ws.output_matrix(m, kTwoPi * freqs_hz[k]);
    ws.response(target);
    if (cache) cache->X[k] = ws.X;
    work.lu_factorizations += 1;
    work.solved_columns += static_cast<std::size_t>(ws.inputs);
    sink(k, ws.H);
  }
  if (cache) cache->valid = true;
  return work;
}

FrfWork frf(const ModelMatrices& m, const std::vector<double>& freqs_hz, const FrfSink& sink) {
  return frf(m, freqs_hz, sink, nullptr);
}

FrfResult frf(const ModelMatrices& m, const std::vector<double>& freqs_hz) {
  FrfResult result;
  result.freqs_hz = freqs_hz;
  result.H.reserve(freqs_hz.size());
  frf(m, freqs_hz, [&](std::size_t, const Eigen::MatrixXcd& H) { result.H.push_back(H); });
  return result;
}

FrfWork frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                     const std::vector<double>& freqs_hz, const FrfJacobianSink& sink) {
  return frf_jacobian(m, d, parameter_count, freqs_hz, sink, nullptr);
}

FrfWork frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                     const std::vector<double>& freqs_hz, const FrfJacobianSink& sink, const FrfFactorCache* known) {
  const char* where = "frf_jacobian";
  detail::check_matrices(m, where);
  detail::check_derivatives(m, d, parameter_count, where);
  check_frequencies(freqs_hz, where);
  Workspace ws(m);
  const Eigen::Index outputs = ws.outputs, inputs = ws.inputs;
  ws.J.resize(outputs * inputs, parameter_count);
  const Eigen::MatrixXcd& X = ws.X;
  const Eigen::MatrixXcd& Yt = ws.Yt;
  Eigen::MatrixXcd& J = ws.J;
  const FrfFactorCache::Impl* cache = known && known->impl().holds(m, freqs_hz) ? &known->impl() : nullptr;
  const GroupedEntries dK(d.K), dC(d.C), dM(d.M);
  FrfWork work;
  for (std::size_t k = 0; k < freqs_hz.size(); ++k) {
    const double w = kTwoPi * freqs_hz[k];
    const cd s(0, w), s2 = s * s;
    ws.output_matrix(m, w);
    // Adjoint solve P^T Y^T = Cout^T; Yt = Y^T (n x outputs) is used directly: Y(o, r) = Yt(r, o).
    ws.Yt = ws.Cout.transpose();
    if (cache) {  // the factors and X of the evaluation just before, at these matrices
      ws.X = cache->X[k];
      ws.H.noalias() = ws.Cout * ws.X;
      cache->lu[k].solve_transposed(ws.Yt);
      work.solved_columns += static_cast<std::size_t>(outputs);
    } else {
      ws.factor(m, freqs_hz[k], where);
      ws.response();
      ws.solve_transposed(ws.Yt);
      work.lu_factorizations += 1;
      work.solved_columns += static_cast<std::size_t>(inputs + outputs);
    }

    // Column p of J is vec(dH/dp_p); entry (o, i) lives in row o + i * outputs. Every derivative term is a sum of
    // row/column updates, written as plain loops: no temporaries.
    J.setZero();
    // -Y dP X, one (parameter, row) group at a time: z = sum over the group's entries of value * X(col, :), then
    // -factor * Y(:, row) z. A spring's derivative b b^T has its |b|^2 entries in |b| rows: the products with Y are
    // made once per row instead of once per entry.
    auto stiffness_term = [&](const GroupedEntries& grouped, cd factor) {
      const std::vector<DerivativeEntry>& entries = grouped.entries;
      for (const EntryGroup& g : grouped.groups) {
        for (Eigen::Index i = 0; i < inputs; ++i) {
          cd z = 0;
          for (std::size_t e = g.first; e < g.last; ++e) z += entries[e].value * X(entries[e].col, i);
          const cd a = -factor * z;
          for (Eigen::Index o = 0; o < outputs; ++o) J(o + i * outputs, g.param) += a * Yt(g.row, o);
        }
      }
    };
    stiffness_term(dK, 1.0);
    stiffness_term(dC, s);
    stiffness_term(dM, s2);
    // Y dB: entry (r, c) adds value * Y(:, r) to FRF column c.
    for (const auto& e : d.B)
      for (Eigen::Index o = 0; o < outputs; ++o) J(o + e.col * outputs, e.param) += e.value * Yt(e.row, o);
    // dCout X: entry (r, c) adds factor * value * X(c, :) to FRF row r.
    auto output_term = [&](const std::vector<DerivativeEntry>& entries, cd factor) {
      for (const auto& e : entries) {
        const cd a = factor * e.value;
        for (Eigen::Index i = 0; i < inputs; ++i) J(e.row + i * outputs, e.param) += a * X(e.col, i);
      }
    };
    output_term(d.Cd, 1.0);
    output_term(d.Cv, s);
    output_term(d.Ca, s2);
    sink(k, ws.H, J);
  }
  return work;
}

FrfJacobianResult frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                               const std::vector<double>& freqs_hz) {
  FrfJacobianResult result;
  result.freqs_hz = freqs_hz;
  result.H.reserve(freqs_hz.size());
  result.dH.reserve(freqs_hz.size());
  const FrfWork work = frf_jacobian(m, d, parameter_count, freqs_hz,
                                    [&](std::size_t, const Eigen::MatrixXcd& H, const Eigen::MatrixXcd& dH) {
                                      result.H.push_back(H);
                                      result.dH.push_back(dH);
                                    });
  result.lu_factorizations = work.lu_factorizations;
  result.solved_columns = work.solved_columns;
  return result;
}

FrfResult frf(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz) {
  detail::check_parameter_vector(model, p, "frf");
  ModelMatrices m;
  model.evaluate(p, m);
  return frf(m, freqs_hz);
}

FrfJacobianResult frf_jacobian(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz) {
  detail::check_parameter_vector(model, p, "frf_jacobian");
  ModelMatrices m;
  ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  return frf_jacobian(m, d, static_cast<int>(p.size()), freqs_hz);
}

}  // namespace mbgen
