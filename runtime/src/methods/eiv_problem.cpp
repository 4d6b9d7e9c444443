#include "eiv_problem.hpp"

#include "estimation/excited_block.hpp"
#include "method_setup.hpp"

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/fftw_mutex.hpp"
#include "mbgen/dynamics/state_space.hpp"
#include "numerics/constants.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace mbgen::methods {

namespace {

using cd = std::complex<double>;

// Lines 1 .. ceil(N/2) - 1 of the DFT of x (FFTW's sign: X_k = sum x_n e^{-2 pi i k n / N}), divided by sqrt(N).
Eigen::VectorXcd spectrum_lines(const Eigen::VectorXd& x, Eigen::Index lines) {
  const Eigen::Index n = x.size();
  double* in = fftw_alloc_real(static_cast<std::size_t>(n));
  fftw_complex* out = fftw_alloc_complex(static_cast<std::size_t>(n / 2 + 1));
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in, out, FFTW_ESTIMATE);  // no timing runs: deterministic
  }
  std::copy(x.data(), x.data() + n, in);
  fftw_execute(plan);
  Eigen::VectorXcd X(lines);
  const double norm = 1 / std::sqrt(double(n));
  for (Eigen::Index k = 0; k < lines; ++k) X[k] = cd(out[k + 1][0], out[k + 1][1]) * norm;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(in);
  fftw_free(out);
  return X;
}

InputHold input_hold(HoldMode hold) { return hold == HoldMode::None ? InputHold::FirstOrder : InputHold::ZeroOrder; }

// Moore-Penrose inverse of a symmetric positive semi-definite matrix (directions below 1e-12 of the largest dropped:
// a state the outputs do not see leaves its transient undetermined, which changes nothing).
Eigen::MatrixXd psd_pinv(const Eigen::MatrixXd& H) {
  if (H.size() == 0) return H;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s[i] > s[0] * 1e-12) inv[i] = 1 / s[i];
  return svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose();
}

}  // namespace

// One record's model (discretised, its derivatives, the noise weights) and its transient at its least-squares value.
// Nothing per line is kept: a line's terms are recomputed where they are needed (line()), so that a long record
// costs memory per sample only in its spectra and the Jacobian.
struct EivProblem::Lines {
  bool ok = false;
  Eigen::Index ns = 0, no = 0, ni = 0;
  Eigen::MatrixXcd Phi, Gamma0, Gamma1, C, D;
  std::vector<Eigen::MatrixXcd> dPhi, dGamma0, dGamma1, dC, dD;  // per free parameter (empty without derivatives)
  Eigen::VectorXd w, v;  // whitening of outputs and inputs: 1 / sigma
  Eigen::MatrixXd Ht;    // sum over lines of Re(Jt^H Jt)
  Eigen::VectorXd t;     // the transient at its least-squares value

  // The terms of line k.
  struct Line {
    Eigen::MatrixXcd Finv;    // (z I - Phi)^-1
    Eigen::MatrixXcd Q;       // C (z I - Phi)^-1
    Eigen::MatrixXcd G;       // outputs x inputs
    Eigen::MatrixXcd A;       // [w G; diag(v)]: the true force's columns
    Eigen::MatrixXcd AHAinv;  // (A^H A)^-1
    Eigen::VectorXcd b;       // whitened data [w Y; v U]
    Eigen::VectorXcd r0;      // b projected off A
    Eigen::MatrixXcd Jt;      // the transient's columns, -[w z Q; 0], projected off A
    bool ok = false;

    Eigen::MatrixXcd project(const Eigen::MatrixXcd& y) const { return y - A * (AHAinv * (A.adjoint() * y)); }
  };
  Line line(const Record& rec, Eigen::Index k) const {
    Line l;
    const cd z = rec.z[k];
    Eigen::MatrixXcd F = -Phi;
    F.diagonal().array() += z;
    l.Finv = Eigen::PartialPivLU<Eigen::MatrixXcd>(F).inverse();
    l.Q = C * l.Finv;
    l.G = l.Q * (Gamma0 + z * Gamma1) + D;
    l.A.resize(no + ni, ni);
    l.A.topRows(no) = w.asDiagonal() * l.G;
    l.A.bottomRows(ni) = v.cast<cd>().asDiagonal();
    l.AHAinv = (l.A.adjoint() * l.A).inverse();
    l.b.resize(no + ni);
    l.b.head(no) = w.asDiagonal() * rec.Y.row(k).transpose();
    l.b.tail(ni) = v.asDiagonal() * rec.U.row(k).transpose();
    l.r0 = l.project(l.b);
    Eigen::MatrixXcd Bt = Eigen::MatrixXcd::Zero(no + ni, ns);
    Bt.topRows(no) = -(z * (w.asDiagonal() * l.Q));
    l.Jt = l.project(Bt);
    l.ok = l.Finv.allFinite() && l.AHAinv.allFinite();
    return l;
  }
};

EivProblem::EivProblem(const Model& model, const std::vector<DataSet>& data, std::vector<int> free,
                       const Eigen::VectorXd& values)
    : model_(model), free_(std::move(free)) {
  const ModelInfo& info = model.info();
  for (std::size_t i = 0; i < info.inputs.size(); ++i) inputs_.push_back(static_cast<int>(i));
  for (const DataSet& d : data) {
    if (d.is_frf())
      throw FitError(d.file() + ": error: --method eiv needs time records (the measured force's own spectrum and "
                     "noise), but this file holds FRFs");
    const TimeRecord& t = std::get<TimeRecord>(d.content);
    require_inputs(t, info.inputs);  // DataError naming the file and the missing force channel
    Record rec;
    rec.file = d.file();
    for (const auto& [name, value] : d.set()) rec.overrides.emplace_back(info.parameter_index(name), value.value);
    for (std::size_t o = 0; o < info.outputs.size(); ++o)
      if (t.find(info.outputs[o])) {
        rec.outputs.push_back(static_cast<int>(o));
        rec.output_names.push_back(info.outputs[o]);
      }
    if (rec.outputs.empty()) throw FitError(rec.file + ": error: the record has none of the model's outputs");
    const Eigen::Index n = t.samples();
    const Eigen::Index lines = n >= 3 ? (n - 1) / 2 : 0;
    // The excited block's states (the transient's size) at the start values.
    ModelMatrices m;
    model.evaluate(values_for(model, d, values), m);
    const auto red = estimation::reduce_to_excited_block(m, nullptr, inputs_, rec.outputs, {});
    rec.states = 2 * red.m.M.rows();
    const Eigen::Index no = static_cast<Eigen::Index>(rec.outputs.size());
    // Each line gives 2 outputs real equations net of the true force; the transient and the parameters take theirs.
    const Eigen::Index unknowns = static_cast<Eigen::Index>(free_.size()) + rec.states;
    if (lines < 32 || 2 * lines * no < 20 * unknowns)
      throw FitError(rec.file + ": error: --method eiv needs a longer record: its " + std::to_string(n) +
                     " samples give " + std::to_string(lines) + " frequency lines, and at least " +
                     std::to_string(std::max<Eigen::Index>(32, (20 * unknowns + 2 * no - 1) / (2 * no))) +
                     " are needed for " + std::to_string(unknowns) + " unknowns (parameters and the record's "
                     "transient)");
    rec.dt = t.dt();
    rec.hold = t.hold;
    rec.z.resize(lines);
    for (Eigen::Index k = 0; k < lines; ++k) {
      const double phase = numerics::kTwoPi * double(k + 1) / double(n);
      rec.z[k] = cd(std::cos(phase), std::sin(phase));
    }
    rec.U.resize(lines, static_cast<Eigen::Index>(info.inputs.size()));
    for (std::size_t i = 0; i < info.inputs.size(); ++i)
      rec.U.col(static_cast<Eigen::Index>(i)) = spectrum_lines(t.at(info.inputs[i]).values, lines);
    rec.Y.resize(lines, no);
    for (Eigen::Index o = 0; o < no; ++o)
      rec.Y.col(o) = spectrum_lines(t.at(rec.output_names[static_cast<std::size_t>(o)]).values, lines);
    rec.offset = rows_;
    const Eigen::Index ni = rec.U.cols();
    rows_ += 2 * (no + ni) * lines;
    nuisance_ += 2 * ni * lines + rec.states;
    records_.push_back(std::move(rec));
  }
}

std::vector<EivNoise> EivProblem::initial_noise() const {
  std::vector<EivNoise> out;
  for (const Record& rec : records_) {
    EivNoise n;
    n.output = 1e-4 * rec.Y.cwiseAbs2().colwise().mean().transpose();
    n.input = 1e-6 * rec.U.cwiseAbs2().colwise().mean().transpose();
    out.push_back(n);
  }
  return out;
}

EivProblem::Lines EivProblem::solve_lines(const Record& rec, const Eigen::VectorXd& values, const EivNoise& noise,
                                          bool derivatives) const {
  Lines L;
  Eigen::VectorXd p = values;
  for (const auto& [idx, v] : rec.overrides) p[idx] = v;
  std::vector<int> column(static_cast<std::size_t>(p.size()), -1);
  for (std::size_t j = 0; j < free_.size(); ++j) column[static_cast<std::size_t>(free_[j])] = static_cast<int>(j);
  for (const auto& [idx, v] : rec.overrides) column[static_cast<std::size_t>(idx)] = -1;
  try {
    ModelMatrices m;
    ModelDerivatives md;
    model_.evaluate(p, m);
    if (derivatives) model_.derivatives(p, md);
    const estimation::ReducedModel red =
        estimation::reduce_to_excited_block(m, derivatives ? &md : nullptr, inputs_, rec.outputs, column);
    const StateSpace ss = state_space(red.m);
    const DiscreteStateSpace dss = discretize(ss, rec.dt, input_hold(rec.hold));
    if (!dss.Phi.allFinite()) return L;
    L.Phi = dss.Phi.cast<cd>();
    L.Gamma0 = dss.Gamma0.cast<cd>();
    L.Gamma1 = dss.Gamma1.cast<cd>();
    L.C = dss.C.cast<cd>();
    L.D = dss.D.cast<cd>();
    if (derivatives)
      for (const DiscreteStateSpace& d :
           discretize_derivatives(ss, state_space_derivatives(red.m, red.d, static_cast<int>(free_.size())), rec.dt,
                                  input_hold(rec.hold))) {
        L.dPhi.push_back(d.Phi.cast<cd>());
        L.dGamma0.push_back(d.Gamma0.cast<cd>());
        L.dGamma1.push_back(d.Gamma1.cast<cd>());
        L.dC.push_back(d.C.cast<cd>());
        L.dD.push_back(d.D.cast<cd>());
      }
  } catch (const std::runtime_error&) {  // DynamicsError: no model at these values (a trial step's failure)
    return L;
  }
  L.ns = L.Phi.rows();
  L.no = static_cast<Eigen::Index>(rec.outputs.size());
  L.ni = rec.U.cols();
  L.w = noise.output.cwiseSqrt().cwiseInverse();
  L.v = noise.input.cwiseSqrt().cwiseInverse();
  L.Ht = Eigen::MatrixXd::Zero(L.ns, L.ns);
  Eigen::VectorXd gt = Eigen::VectorXd::Zero(L.ns);
  for (Eigen::Index k = 0; k < rec.z.size(); ++k) {
    const Lines::Line l = L.line(rec, k);
    if (!l.ok) return Lines{};
    L.Ht += (l.Jt.adjoint() * l.Jt).real();
    gt += (l.Jt.adjoint() * l.r0).real();
  }
  L.t = -(psd_pinv(L.Ht) * gt);
  L.ok = L.t.allFinite();
  return L;
}

bool EivProblem::evaluate(const Eigen::VectorXd& values, const std::vector<EivNoise>& noise, Eigen::VectorXd& r,
                          Eigen::MatrixXd* J) const {
  const Eigen::Index nk = static_cast<Eigen::Index>(free_.size());
  r.resize(rows_);
  if (J) J->setZero(rows_, nk);
  for (std::size_t ri = 0; ri < records_.size(); ++ri) {
    const Record& rec = records_[ri];
    const Lines L = solve_lines(rec, values, noise[ri], J != nullptr);
    if (!L.ok) return false;
    const Eigen::Index lines = rec.z.size(), ns = L.ns, no = L.no, ni = L.ni, width = 2 * (no + ni);
    const Eigen::VectorXcd t = L.t.cast<cd>();
    Eigen::MatrixXd Jt_real(J ? width * lines : 0, ns);
    for (Eigen::Index k = 0; k < lines; ++k) {
      const Lines::Line l = L.line(rec, k);
      const Eigen::Index row = rec.offset + k * width;
      const Eigen::VectorXcd res = l.r0 + l.Jt * t;
      r.segment(row, no + ni) = res.real();
      r.segment(row + no + ni, no + ni) = res.imag();
      if (!J) continue;
      Jt_real.block(k * width, 0, no + ni, ns) = l.Jt.real();
      Jt_real.block(k * width + no + ni, 0, no + ni, ns) = l.Jt.imag();
      // The true force at its least-squares value, and the state spectrum it and the transient give.
      const cd z = rec.z[k];
      Eigen::VectorXcd b = l.b;
      b.head(no) -= z * (L.w.asDiagonal() * (l.Q * t));
      const Eigen::VectorXcd U0 = l.AHAinv * (l.A.adjoint() * b);
      const Eigen::VectorXcd x = l.Finv * ((L.Gamma0 + z * L.Gamma1) * U0 + z * t);
      // Each parameter's column at fixed U0 and t, then projected off U0's (Kaufman).
      Eigen::MatrixXcd cols = Eigen::MatrixXcd::Zero(no + ni, nk);
      for (Eigen::Index j = 0; j < nk; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const Eigen::VectorXcd dstate = L.dPhi[jj] * x + (L.dGamma0[jj] + z * L.dGamma1[jj]) * U0;
        const Eigen::VectorXcd dy = L.dC[jj] * x + l.Q * dstate + L.dD[jj] * U0;
        cols.col(j).head(no) = -(L.w.cast<cd>().asDiagonal() * dy);
      }
      const Eigen::MatrixXcd proj = l.project(cols);
      J->block(row, 0, no + ni, nk) = proj.real();
      J->block(row + no + ni, 0, no + ni, nk) = proj.imag();
    }
    if (J && ns > 0) {
      // Kaufman's projection off the transient's columns too (eliminated over the whole record).
      auto block = J->middleRows(rec.offset, width * lines);
      const Eigen::MatrixXd coupling = Jt_real.transpose() * block;
      block -= Jt_real * (psd_pinv(L.Ht) * coupling);
    }
  }
  return r.allFinite() && (!J || J->allFinite());
}

std::vector<EivNoise> EivProblem::estimate_noise(const Eigen::VectorXd& values,
                                                 const std::vector<EivNoise>& noise) const {
  std::vector<EivNoise> out;
  for (std::size_t ri = 0; ri < records_.size(); ++ri) {
    const Record& rec = records_[ri];
    const Lines L = solve_lines(rec, values, noise[ri], false);
    if (!L.ok) throw FitError("fit --method eiv: the model cannot be evaluated at the estimate");
    const Eigen::Index lines = rec.z.size(), no = L.no, ni = L.ni;
    const Eigen::VectorXcd t = L.t.cast<cd>();
    // Observations |e_o|^2 and the regressors |G_oi|^2 of the variance model.
    Eigen::MatrixXd e2(lines, no);
    std::vector<Eigen::MatrixXd> g2(static_cast<std::size_t>(ni), Eigen::MatrixXd(lines, no));
    for (Eigen::Index k = 0; k < lines; ++k) {
      const Lines::Line l = L.line(rec, k);
      const Eigen::VectorXcd e =
          rec.Y.row(k).transpose() - l.G * rec.U.row(k).transpose() - rec.z[k] * (l.Q * t);
      e2.row(k) = e.cwiseAbs2().transpose();
      for (Eigen::Index i = 0; i < ni; ++i) g2[static_cast<std::size_t>(i)].row(k) = l.G.col(i).cwiseAbs2().transpose();
    }
    // Fisher scoring for exponential observations with mean a_o + sum_i b_i g2_i (identity link): weighted least
    // squares with weights 1 / mean^2, repeated. Floors: 1e-10 of the signals' mean line power.
    const Eigen::Index np = no + ni;
    Eigen::VectorXd theta(np), floor(np);
    theta << noise[ri].output, noise[ri].input;
    floor << 1e-10 * rec.Y.cwiseAbs2().colwise().mean().transpose(), 1e-10 * rec.U.cwiseAbs2().colwise().mean().transpose();
    theta = theta.cwiseMax(floor);
    for (int iteration = 0; iteration < 50; ++iteration) {
      Eigen::MatrixXd N = Eigen::MatrixXd::Zero(np, np);
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(np);
      Eigen::VectorXd x(np);
      for (Eigen::Index k = 0; k < lines; ++k)
        for (Eigen::Index o = 0; o < no; ++o) {
          x.setZero();
          x[o] = 1;
          for (Eigen::Index i = 0; i < ni; ++i) x[no + i] = g2[static_cast<std::size_t>(i)](k, o);
          const double mean = x.dot(theta), weight = 1 / (mean * mean);
          N.noalias() += weight * x * x.transpose();
          rhs += weight * e2(k, o) * x;
        }
      // Scale the unknowns to the floors' size for a well-conditioned solve.
      const Eigen::VectorXd s = floor.cwiseMax(1e-300);
      const Eigen::MatrixXd Ns = s.asDiagonal() * N * s.asDiagonal();
      const Eigen::VectorXd next = (s.asDiagonal() * psd_pinv(Ns) * (s.asDiagonal() * rhs)).cwiseMax(floor);
      const double change = ((next - theta).cwiseAbs().cwiseQuotient(theta)).maxCoeff();
      theta = next;
      if (change < 1e-8) break;
    }
    EivNoise n;
    n.output = theta.head(no);
    n.input = theta.tail(ni);
    out.push_back(n);
  }
  return out;
}

}  // namespace mbgen::methods
