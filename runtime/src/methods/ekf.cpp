#include "mbgen/methods/ekf.hpp"

#include "method_result.hpp"
#include "method_setup.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen/dynamics/state_space.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mbgen {

namespace {

using methods::MethodSetup;

// One record, prepared: inputs (samples x inputs), the model outputs it measures and their samples.
struct Record {
  const DataSet* set = nullptr;
  Eigen::MatrixXd u;
  Eigen::MatrixXd y;          // samples x measured outputs
  std::vector<int> outputs;   // model output index of each column of y
  std::vector<std::string> names;
  double dt = 0;
  InputHold hold = InputHold::ZeroOrder;
  std::vector<bool> overridden;  // per estimated parameter: fixed by a `# set` line of this record
};

Record prepare(const Model& model, const DataSet& d, const MethodSetup& setup) {
  const ModelInfo& info = model.info();
  const TimeRecord& t = std::get<TimeRecord>(d.content);
  Record r;
  r.set = &d;
  require_inputs(t, info.inputs);
  if (t.samples() < 8) throw FitError(d.file() + ": error: --method ekf needs a record of at least 8 samples");
  r.u.resize(t.samples(), static_cast<Eigen::Index>(info.inputs.size()));
  for (std::size_t i = 0; i < info.inputs.size(); ++i) r.u.col(static_cast<Eigen::Index>(i)) = t.at(info.inputs[i]).values;
  for (std::size_t o = 0; o < info.outputs.size(); ++o)
    if (t.find(info.outputs[o])) {
      r.outputs.push_back(static_cast<int>(o));
      r.names.push_back(info.outputs[o]);
    }
  if (r.outputs.empty()) throw FitError(d.file() + ": error: the record holds none of the model's outputs");
  r.y.resize(t.samples(), static_cast<Eigen::Index>(r.outputs.size()));
  for (std::size_t c = 0; c < r.names.size(); ++c) r.y.col(static_cast<Eigen::Index>(c)) = t.at(r.names[c]).values;
  r.dt = t.dt();
  r.hold = t.hold == HoldMode::None ? InputHold::FirstOrder : InputHold::ZeroOrder;
  for (int i : setup.candidates) r.overridden.push_back(d.set().count(info.parameters[static_cast<std::size_t>(i)].name) > 0);
  return r;
}

// Measurement noise variance per output from its 4th differences: white noise of variance s^2 gives
// var(D^4 y) = 70 s^2 (1 + 16 + 36 + 16 + 1), while a signal sampled well above its frequencies is nearly
// cancelled; so this is an upper estimate that is close when the record is oversampled.
Eigen::VectorXd difference_noise(const Eigen::MatrixXd& y) {
  Eigen::VectorXd r(y.cols());
  for (Eigen::Index c = 0; c < y.cols(); ++c) {
    double sum = 0;
    for (Eigen::Index k = 4; k < y.rows(); ++k) {
      const double d4 = y(k, c) - 4 * y(k - 1, c) + 6 * y(k - 2, c) - 4 * y(k - 3, c) + y(k - 4, c);
      sum += d4 * d4;
    }
    r[c] = sum / double(y.rows() - 4) / 70;
  }
  return r;
}

// The floor of a measurement noise variance: 1e-4 of the output's RMS (80 dB), so that noise-free data do not
// make the filter trust every sample infinitely.
Eigen::VectorXd noise_floor(const Eigen::MatrixXd& y) {
  return (y.colwise().squaredNorm().transpose() / double(y.rows()) * 1e-8).cwiseMax(1e-300);
}

// The discretised model and its theta-derivatives at one theta, in scaled state coordinates x = S xs.
struct Linearization {
  Eigen::VectorXd theta;
  Eigen::MatrixXd Phi, G0, G1, C, D;
  std::vector<Eigen::MatrixXd> dPhi, dG0, dG1, dC, dD;
};

class Filter {
 public:
  Filter(const Model& model, const MethodSetup& setup, const EkfOptions& ekf, double total_duration)
      : model_(model), setup_(setup), ekf_(ekf) {
    const auto np = static_cast<Eigen::Index>(setup.candidates.size());
    theta0_.resize(np);
    q_rate_.resize(np);
    P0_.setZero(np, np);
    for (Eigen::Index j = 0; j < np; ++j) {
      const int i = setup.candidates[static_cast<std::size_t>(j)];
      const ParameterTransform& t = setup.transforms[static_cast<std::size_t>(i)];
      theta0_[j] = t.to_internal(setup.prior[i]);
      // A relative size in physical units, as a size in theta at the prior.
      const double reference = setup.prior[i] != 0 ? std::abs(setup.prior[i]) : t.scale;
      const double per_theta = reference / std::max(std::abs(t.derivative(theta0_[j])), 1e-300);
      P0_(j, j) = std::pow(ekf.initial_std * per_theta, 2);
      q_rate_[j] = std::pow(ekf.drift * per_theta, 2) / total_duration;
    }
  }

  Eigen::VectorXd physical(const Eigen::VectorXd& theta) const {
    Eigen::VectorXd p = setup_.prior;
    for (std::size_t j = 0; j < setup_.candidates.size(); ++j) {
      const int i = setup_.candidates[j];
      p[i] = setup_.transforms[static_cast<std::size_t>(i)].to_physical(theta[static_cast<Eigen::Index>(j)]);
    }
    return p;
  }
  Eigen::VectorXd slopes(const Eigen::VectorXd& theta) const {  // dp/dtheta
    Eigen::VectorXd g(theta.size());
    for (std::size_t j = 0; j < setup_.candidates.size(); ++j)
      g[static_cast<Eigen::Index>(j)] =
          setup_.transforms[static_cast<std::size_t>(setup_.candidates[j])].derivative(theta[static_cast<Eigen::Index>(j)]);
    return g;
  }

  struct Pass {
    Eigen::VectorXd theta;
    Eigen::MatrixXd P;
    // Per record and output: sum of innovation^2, of its predicted variance less R, of innovation^2 / S, and count,
    // over the record's second half (the noise estimate) and whole (the normalised innovations).
    std::vector<Eigen::VectorXd> nu2_late, hph_late, nis;
    std::vector<double> late_count;
    // Trajectory (every `stride`-th sample).
    std::vector<int> traj_record;
    std::vector<double> traj_t;
    std::vector<Eigen::VectorXd> traj_theta, traj_var;
    int relinearizations = 0;
  };

  Pass run(const std::vector<Record>& records, const std::vector<Eigen::VectorXd>& R, int stride) const {
    const auto np = static_cast<Eigen::Index>(setup_.candidates.size());
    Pass pass;
    pass.theta = theta0_;
    pass.P = P0_;
    long global = 0;
    for (std::size_t rec = 0; rec < records.size(); ++rec) {
      const Record& r = records[rec];
      const TimeRecord& tr = std::get<TimeRecord>(r.set->content);
      const Eigen::Index N = r.u.rows(), ny = r.y.cols();
      state_scale_ = state_scale(r, pass.theta);
      const Eigen::Index nx = state_scale_.size(), nz = nx + np;
      Eigen::VectorXd x = Eigen::VectorXd::Zero(nx);  // from rest, as the data convention has it
      Eigen::MatrixXd P = Eigen::MatrixXd::Zero(nz, nz);
      P.topLeftCorner(nx, nx).setIdentity();  // scaled coordinates: the state's own size
      P.bottomRightCorner(np, np) = pass.P;
      Eigen::VectorXd nu2 = Eigen::VectorXd::Zero(ny), hph = Eigen::VectorXd::Zero(ny), nis = Eigen::VectorXd::Zero(ny);
      double late = 0;
      Linearization lin;
      bool have = false;
      const Eigen::MatrixXd Ry = R[rec].asDiagonal();
      Eigen::MatrixXd H(ny, nz), F = Eigen::MatrixXd::Identity(nz, nz);
      for (Eigen::Index k = 0; k < N; ++k) {
        Eigen::VectorXd theta = pass.theta;
        if (!have || (theta - lin.theta).cwiseAbs().maxCoeff() > ekf_.relinearize) {
          lin = linearize(r, theta, tr.t[k]);
          have = true;
          ++pass.relinearizations;
        }
        const Eigen::VectorXd dth = theta - lin.theta;
        // Measurement update with y_k.
        const Eigen::VectorXd uk = r.u.row(k).transpose();
        Eigen::MatrixXd C = lin.C, D = lin.D;
        for (Eigen::Index j = 0; j < np; ++j) {
          C += dth[j] * lin.dC[static_cast<std::size_t>(j)];
          D += dth[j] * lin.dD[static_cast<std::size_t>(j)];
        }
        H.leftCols(nx) = C;
        for (Eigen::Index j = 0; j < np; ++j)
          H.col(nx + j) = lin.dC[static_cast<std::size_t>(j)] * x + lin.dD[static_cast<std::size_t>(j)] * uk;
        const Eigen::VectorXd nu = r.y.row(k).transpose() - (C * x + D * uk);
        const Eigen::MatrixXd PHt = P * H.transpose();
        const Eigen::MatrixXd S = H * PHt + Ry;
        const Eigen::LLT<Eigen::MatrixXd> llt(S);
        if (llt.info() != Eigen::Success || !nu.allFinite())
          throw FitError(where(r, tr.t[k]) + "the filter diverged (innovation covariance not positive definite)");
        const Eigen::MatrixXd Kg = llt.solve(PHt.transpose()).transpose();
        x += Kg.topRows(nx) * nu;
        pass.theta += Kg.bottomRows(np) * nu;
        const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(nz, nz) - Kg * H;
        P = IKH * P * IKH.transpose() + Kg * Ry * Kg.transpose();  // Joseph form: stays symmetric and positive
        P = 0.5 * (P + P.transpose()).eval();
        nis += nu.cwiseAbs2().cwiseQuotient(S.diagonal());
        if (2 * k >= N) {
          nu2 += nu.cwiseAbs2();
          hph += S.diagonal() - R[rec];
          late += 1;
        }
        if (global % stride == 0 || k == N - 1) {
          pass.traj_record.push_back(static_cast<int>(rec));
          pass.traj_t.push_back(tr.t[k]);
          pass.traj_theta.push_back(pass.theta);
          pass.traj_var.push_back(P.bottomRightCorner(np, np).diagonal());
        }
        ++global;
        if (k == N - 1) break;
        // Prediction to k + 1, at the updated theta.
        const Eigen::VectorXd d2 = pass.theta - lin.theta;
        const Eigen::VectorXd uk1 = r.u.row(k + 1).transpose();
        Eigen::MatrixXd Phi = lin.Phi, G0 = lin.G0, G1 = lin.G1;
        for (Eigen::Index j = 0; j < np; ++j) {
          Phi += d2[j] * lin.dPhi[static_cast<std::size_t>(j)];
          G0 += d2[j] * lin.dG0[static_cast<std::size_t>(j)];
          G1 += d2[j] * lin.dG1[static_cast<std::size_t>(j)];
        }
        F.topLeftCorner(nx, nx) = Phi;
        for (Eigen::Index j = 0; j < np; ++j) {
          const auto js = static_cast<std::size_t>(j);
          F.block(0, nx + j, nx, 1) = lin.dPhi[js] * x + lin.dG0[js] * uk + lin.dG1[js] * uk1;
        }
        x = Phi * x + G0 * uk + G1 * uk1;
        P = F * P * F.transpose();
        for (Eigen::Index j = 0; j < np; ++j) P(nx + j, nx + j) += q_rate_[j] * r.dt;
        if (!x.allFinite() || !pass.theta.allFinite())
          throw FitError(where(r, tr.t[k]) + "the filter diverged (non-finite state)");
      }
      pass.P = P.bottomRightCorner(np, np);
      pass.nu2_late.push_back(nu2);
      pass.hph_late.push_back(hph);
      pass.late_count.push_back(late);
      pass.nis.push_back(nis / double(N));
    }
    return pass;
  }

 private:
  static std::string where(const Record& r, double t) {
    std::ostringstream s;
    s << r.set->file() << ": error: --method ekf: at t = " << t << " s ";
    return s.str();
  }

  // RMS of each state component when the model at theta is driven by the record's input from rest: the size of
  // the state's motion, which scales the filter's state coordinates and its initial state covariance.
  Eigen::VectorXd state_scale(const Record& r, const Eigen::VectorXd& theta) const {
    ModelMatrices m;
    model_.evaluate(methods::values_for(model_, *r.set, physical(theta)), m);
    const DiscreteStateSpace ds = discretize(state_space(m), r.dt, r.hold);
    const Eigen::Index nx = ds.Phi.rows(), n = nx / 2;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(nx), sum = Eigen::VectorXd::Zero(nx);
    for (Eigen::Index k = 0; k + 1 < r.u.rows(); ++k) {
      x = ds.Phi * x + ds.Gamma0 * r.u.row(k).transpose() + ds.Gamma1 * r.u.row(k + 1).transpose();
      sum += x.cwiseAbs2();
    }
    Eigen::VectorXd s = (sum / double(r.u.rows())).cwiseSqrt();
    // An unexcited coordinate still needs a scale: a thousandth of the largest of its kind.
    for (Eigen::Index half = 0; half < 2; ++half) {
      const double top = s.segment(half * n, n).maxCoeff();
      for (Eigen::Index i = half * n; i < (half + 1) * n; ++i) s[i] = std::max(s[i], top > 0 ? 1e-3 * top : 1.0);
    }
    return s;
  }

  Linearization linearize(const Record& r, const Eigen::VectorXd& theta, double t) const {
    const auto np = static_cast<Eigen::Index>(setup_.candidates.size());
    const Eigen::VectorXd p = methods::values_for(model_, *r.set, physical(theta));
    const Eigen::VectorXd g = slopes(theta);
    ModelMatrices m;
    ModelDerivatives d;
    Linearization lin;
    lin.theta = theta;
    try {
      model_.evaluate(p, m);
      model_.derivatives(p, d);
      const StateSpace ss = state_space(m);
      const std::vector<StateSpace> all = state_space_derivatives(m, d, static_cast<int>(p.size()));
      std::vector<StateSpace> dss;
      for (Eigen::Index j = 0; j < np; ++j) {
        StateSpace s = all[static_cast<std::size_t>(setup_.candidates[static_cast<std::size_t>(j)])];
        const double f = r.overridden[static_cast<std::size_t>(j)] ? 0.0 : g[j];  // `# set` holds it in this record
        s.A *= f;
        s.B *= f;
        s.C *= f;
        s.D *= f;
        dss.push_back(s);
      }
      const DiscreteStateSpace dd = discretize(ss, r.dt, r.hold);
      const std::vector<DiscreteStateSpace> ddd = discretize_derivatives(ss, dss, r.dt, r.hold);
      const Eigen::VectorXd& S = state_scale_;
      const Eigen::VectorXd Si = S.cwiseInverse();
      auto sc = [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(Si.asDiagonal() * X * S.asDiagonal()); };
      auto sl = [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(Si.asDiagonal() * X); };
      auto sr = [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(X * S.asDiagonal()); };
      auto rows = [&](const Eigen::MatrixXd& X) {  // the measured outputs' rows
        Eigen::MatrixXd out(static_cast<Eigen::Index>(r.outputs.size()), X.cols());
        for (std::size_t c = 0; c < r.outputs.size(); ++c) out.row(static_cast<Eigen::Index>(c)) = X.row(r.outputs[c]);
        return out;
      };
      lin.Phi = sc(dd.Phi);
      lin.G0 = sl(dd.Gamma0);
      lin.G1 = sl(dd.Gamma1);
      lin.C = sr(rows(dd.C));
      lin.D = rows(dd.D);
      for (const DiscreteStateSpace& x : ddd) {
        lin.dPhi.push_back(sc(x.Phi));
        lin.dG0.push_back(sl(x.Gamma0));
        lin.dG1.push_back(sl(x.Gamma1));
        lin.dC.push_back(sr(rows(x.C)));
        lin.dD.push_back(rows(x.D));
      }
    } catch (const DynamicsError& e) {
      throw FitError(where(r, t) + "the model cannot be evaluated at the filter's estimate (" + e.what() + ")");
    }
    return lin;
  }

  const Model& model_;
  const MethodSetup& setup_;
  const EkfOptions& ekf_;
  Eigen::VectorXd theta0_, q_rate_;
  Eigen::MatrixXd P0_;
  mutable Eigen::VectorXd state_scale_;  // of the record being filtered
};

nlohmann::json numbers(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(std::isfinite(v[i]) ? nlohmann::json(v[i]) : nlohmann::json());
  return a;
}

}  // namespace

FitResult fit_ekf(const Model& model, const std::vector<DataSet>& data, const FitOptions& options, const EkfOptions& ekf) {
  const MethodSetup setup = methods::method_setup(model, data, options, "ekf");
  if (!(ekf.drift >= 0) || !(ekf.initial_std > 0) || ekf.passes < 1 || !(ekf.relinearize > 0) || ekf.trajectory_points < 2)
    throw FitError("fit: --method ekf: drift must be >= 0, the initial std > 0, passes >= 1");
  std::vector<Record> records;
  double duration = 0;
  long samples = 0;
  for (const DataSet& d : data) {
    records.push_back(prepare(model, d, setup));
    duration += records.back().dt * double(records.back().u.rows() - 1);
    samples += static_cast<long>(records.back().u.rows());
  }
  const Filter filter(model, setup, ekf, duration);
  const int stride = static_cast<int>(std::max<long>(1, (samples + ekf.trajectory_points - 1) / ekf.trajectory_points));

  std::vector<Eigen::VectorXd> R, R_initial;
  for (const Record& r : records) R.push_back(difference_noise(r.y).cwiseMax(noise_floor(r.y)));
  R_initial = R;
  Filter::Pass pass;
  for (int p = 0; p < ekf.passes; ++p) {
    pass = filter.run(records, R, stride);
    if (p + 1 == ekf.passes) break;
    for (std::size_t i = 0; i < records.size(); ++i)
      R[i] = ((pass.nu2_late[i] - pass.hph_late[i]) / std::max(pass.late_count[i], 1.0)).cwiseMax(noise_floor(records[i].y));
  }

  const Eigen::VectorXd values = filter.physical(pass.theta);
  // Every candidate estimated, with the filter's covariance of them at the end of the data; scored with the
  // default weighting (records: it does not apply) and tolerances.
  methods::MethodOutcome outcome;
  outcome.method = "ekf";
  outcome.prior = setup.prior;
  outcome.values = values;
  for (int i : setup.candidates) {
    outcome.parameters.push_back(methods::estimated_parameter(i));
    outcome.estimated.push_back(model.info().parameters[static_cast<std::size_t>(i)].name);
  }
  const Eigen::VectorXd g = filter.slopes(pass.theta);
  outcome.covariance = g.asDiagonal() * pass.P * g.asDiagonal();
  outcome.std_from_covariance = true;
  outcome.scored = setup.candidates;
  outcome.fitted = static_cast<int>(setup.candidates.size());
  FitResult result;
  methods::finish_result(model, data, FitOptions{}, outcome, result);
  result.iterations = ekf.passes;
  result.converged = true;
  result.stop_reason = "end of data";

  nlohmann::json j;
  j["drift"] = ekf.drift;
  j["initial_std"] = ekf.initial_std;
  j["passes"] = ekf.passes;
  j["relinearizations"] = pass.relinearizations;
  nlohmann::json noise = nlohmann::json::array();
  for (std::size_t i = 0; i < records.size(); ++i)
    for (std::size_t c = 0; c < records[i].names.size(); ++c) {
      const auto ci = static_cast<Eigen::Index>(c);
      noise.push_back({{"data", records[i].set->file()},
                       {"output", records[i].names[c]},
                       {"sigma", std::sqrt(R[i][ci])},
                       {"sigma_differences", std::sqrt(R_initial[i][ci])},
                       // mean of innovation^2 / its predicted variance in the last pass: 1 for a consistent filter
                       {"normalized_innovation", pass.nis[i][ci]}});
    }
  j["measurement_noise"] = noise;
  nlohmann::json traj;
  traj["parameters"] = result.estimated;
  traj["data"] = pass.traj_record;
  traj["t"] = pass.traj_t;
  nlohmann::json value = nlohmann::json::object(), sd = nlohmann::json::object();
  for (std::size_t jj = 0; jj < setup.candidates.size(); ++jj) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(pass.traj_t.size())), s(v.size());
    for (std::size_t k = 0; k < pass.traj_t.size(); ++k) {
      const Eigen::VectorXd p = filter.physical(pass.traj_theta[k]);
      const Eigen::VectorXd gk = filter.slopes(pass.traj_theta[k]);
      const auto jx = static_cast<Eigen::Index>(jj);
      v[static_cast<Eigen::Index>(k)] = p[setup.candidates[jj]];
      s[static_cast<Eigen::Index>(k)] = std::abs(gk[jx]) * std::sqrt(std::max(pass.traj_var[k][jx], 0.0));
    }
    value[result.estimated[jj]] = numbers(v);
    sd[result.estimated[jj]] = numbers(s);
  }
  traj["value"] = value;
  traj["std"] = sd;
  j["trajectory"] = traj;
  result.method_details["ekf"] = j.dump();
  return result;
}

}  // namespace mbgen
