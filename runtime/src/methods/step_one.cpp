#include "step_one.hpp"

#include "armax.hpp"
#include "arx.hpp"
#include "model_coefficients.hpp"
#include "rational_fit.hpp"
#include "mbgen/data/frf_noise.hpp"
#include "numerics/polynomial_roots.hpp"
#include "polynomial.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace mbgen::methods {

namespace {

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json array(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(number(v[i]));
  return a;
}

// The model's structure for one input and its outputs: the pattern and each channel's numerator degree.
StepOneTf structure(const Model& model, const std::string& file, const Eigen::VectorXd& values, int input,
                    const std::vector<int>& outputs, const std::vector<int>& candidates) {
  const ModelInfo& info = model.info();
  StepOneTf s;
  s.file = file;
  s.input = input;
  s.outputs = outputs;
  try {
    s.pattern = structural_pattern(model, values, input, outputs, candidates);
  } catch (const std::runtime_error& e) {
    throw FitError(file + ": error: two-step: the model's transfer functions from " +
                   info.inputs[static_cast<std::size_t>(input)] + " cannot be computed: " + e.what());
  }
  for (std::size_t c = 0; c < outputs.size(); ++c) {
    bool any = false;
    for (bool b : s.pattern[1 + c]) any = any || b;
    if (!any)
      throw FitError(file + ": error: two-step: the model's transfer function " +
                     info.outputs[static_cast<std::size_t>(outputs[c])] + "/" +
                     info.inputs[static_cast<std::size_t>(input)] +
                     " is zero (the output does not see the input's block): nothing to compare its coefficients with");
  }
  return s;
}

std::vector<int> degrees(const StepOneTf& s) {
  std::vector<int> out;
  for (std::size_t c = 1; c < s.pattern.size(); ++c) {
    int d = 0;
    for (std::size_t j = 0; j < s.pattern[c].size(); ++j)
      if (s.pattern[c][j]) d = static_cast<int>(j);
    out.push_back(d);
  }
  return out;
}

// Where the identified order 2m is below the model's q: compare all coefficients up to the model's relative degree
// q - d_c at the lower order, against the model truncated to the identified modes.
void truncate_if_short(StepOneTf& s, const std::vector<int>& model_degree) {
  const int q = static_cast<int>(s.pattern[0].size()) - 1, order = s.tf.order();
  if (order >= q) return;
  s.pattern.assign(1, std::vector<bool>(static_cast<std::size_t>(order + 1), true));
  for (std::size_t c = 0; c < model_degree.size(); ++c) {
    const int d = order - (q - model_degree[c]);
    std::vector<bool> p(static_cast<std::size_t>(std::max(d, 0) + 1), false);
    for (int j = 0; j <= d; ++j) p[static_cast<std::size_t>(j)] = true;
    s.pattern.push_back(p);
  }
  s.truncated_to.clear();
  for (const auto& r : numerics::polynomial_roots(s.tf.denominator))
    if (r.imag() > 0) s.truncated_to.push_back(r);
}

// One ARMAX order's search and coefficients (docs/methods.md#two-step): which start won, the iterations, C's root
// nearest the unit circle, and the coefficients of A(q), B_o(q), C(q) (ascending lags) with their std.
nlohmann::json armax_order_json(const ArmaxEstimate& e, const std::vector<std::string>& outputs) {
  nlohmann::json starts = nlohmann::json::object();
  for (const auto& [name, cost] : e.start_costs) starts[name] = number(cost);
  const Eigen::VectorXd sd = e.covariance.diagonal().cwiseMax(0).cwiseSqrt();
  Eigen::Index k = 0;
  auto with_std = [&](const Eigen::VectorXd& v) {
    nlohmann::json values = nlohmann::json::array(), stds = nlohmann::json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i, ++k) {
      values.push_back(number(v[i]));
      stds.push_back(number(sd[k]));
    }
    return nlohmann::json{{"values", values}, {"std", stds}};
  };
  nlohmann::json coefficients;
  coefficients["a"] = with_std(e.a);
  nlohmann::json b = nlohmann::json::object();
  for (std::size_t o = 0; o < e.b.size(); ++o) b[outputs[o]] = with_std(e.b[o]);
  coefficients["b"] = b;
  coefficients["b_first_lag"] = e.first_lag;
  coefficients["c"] = with_std(e.c);
  return {{"start", e.start},
          {"start_costs", starts},
          {"iterations", e.iterations},
          {"converged", e.converged},
          {"largest_c_root", number(e.largest_c_root)},
          {"c_reflections", e.reflections},
          {"coefficients", coefficients}};
}

nlohmann::json tf_json(const StepOneTf& s) {
  nlohmann::json j;
  j["denominator"] = array(s.tf.denominator);
  nlohmann::json num;
  for (std::size_t c = 0; c < s.tf.outputs.size(); ++c) num[s.tf.outputs[c]] = array(s.tf.numerators[c]);
  j["numerators"] = num;
  j["covariance"] = s.tf.covariance.size() ? nlohmann::json("available") : nlohmann::json(nullptr);
  j["covariance_note"] = s.tf.covariance_note;
  return j;
}

}  // namespace

StepOne run_step_one(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& prior,
                     const std::vector<int>& candidates, const TwoStepOptions& options, int threads) {
  const ModelInfo& info = model.info();
  StepOne out;
  out.details = nlohmann::json::array();
  for (const DataSet& d : data) {
    Eigen::VectorXd values = prior;
    std::vector<std::pair<int, double>> overrides;
    for (const auto& [name, v] : d.set()) {
      const int idx = info.parameter_index(name);
      if (idx >= 0) {
        values[idx] = v.value;
        overrides.emplace_back(idx, v.value);
      }
    }
    if (d.is_frf()) {
      const FrfData& f = std::get<FrfData>(d.content);
      std::map<int, std::vector<std::size_t>> by_input;  // model input -> channels
      for (std::size_t c = 0; c < f.channels.size(); ++c)
        by_input[info.input_index(f.channels[c].input)].push_back(c);
      const Eigen::VectorXd omega = numerics::kTwoPi * f.f_hz;
      for (const auto& [input, channels] : by_input) {
        std::vector<int> outputs;
        for (std::size_t c : channels) outputs.push_back(info.output_index(f.channels[c].output));
        StepOneTf s = structure(model, f.file, values, input, outputs, candidates);
        s.overrides = overrides;
        s.band_lo_hz = f.f_hz.minCoeff();
        s.band_hi_hz = f.f_hz.maxCoeff();
        const std::vector<int> deg = degrees(s);
        const int q = static_cast<int>(s.pattern[0].size()) - 1;
        std::vector<RationalChannel> rc;
        for (std::size_t k = 0; k < channels.size(); ++k) {
          const FrfChannel& ch = f.channels[channels[k]];
          rc.push_back({ch.output, ch.values, frf_noise(f.f_hz, ch).sigma / std::sqrt(2.0), deg[k]});
        }
        // The scale of s: the model's geometric mean natural frequency |a_0|^(1/q), else the band's middle.
        const ModelTf mt = model_tf(model, values, input, outputs, {});
        const double a0 = std::abs(mt.denominator[0]);
        const double omega0 = a0 > 0 ? std::pow(a0, 1.0 / q) : std::sqrt(std::max(omega.minCoeff(), 1e-3) * omega.maxCoeff());
        // From the model's order down: a mode of the fit that is unstable, overdamped, outside the band or below
        // kMinPeak noise standard deviations on every line of every channel is not shown by the data; the fit is
        // then repeated with as many modes as are shown.
        constexpr double kMinPeak = 5;
        RationalFitReport rep;
        nlohmann::json dropped = nlohmann::json::array();
        for (int modes = q / 2;;) {
          const int order = 2 * modes;
          for (std::size_t k = 0; k < rc.size(); ++k) rc[k].numerator_degree = std::max(order - (q - deg[k]), 0);
          try {
            s.tf = fit_rational_frf(omega, rc, f.channels[channels.front()].input, order, omega0, &rep);
          } catch (const std::invalid_argument& e) {
            throw FitError(f.file + ": error: two-step: " + e.what());
          }
          Eigen::VectorXd dD = Eigen::VectorXd::Zero(order);
          for (int k = 1; k <= order; ++k) dD[k - 1] = k * s.tf.denominator[k];
          int shown = 0;
          for (const std::complex<double>& l : numerics::polynomial_roots(s.tf.denominator)) {
            if (l.imag() <= 0) continue;
            const double fz = std::abs(l) / numerics::kTwoPi, zeta = -l.real() / std::abs(l);
            double peak = 0;
            for (std::size_t c = 0; c < rc.size(); ++c) {
              const std::complex<double> r = poly_eval(s.tf.numerators[c], l) / poly_eval(dD, l);
              for (Eigen::Index k = 0; k < omega.size(); ++k) {
                const std::complex<double> iw(0, omega[k]);
                peak = std::max(peak, std::abs(r / (iw - l) + std::conj(r) / (iw - std::conj(l))) /
                                          (std::sqrt(2.0) * rc[c].sigma[k]));
              }
            }
            std::string why;
            if (l.real() >= 0) why = "unstable";
            else if (zeta > 0.3) why = "overdamped (zeta above 0.3)";
            else if (fz < s.band_lo_hz || fz > s.band_hi_hz) why = "outside the band";
            else if (peak < kMinPeak) why = "below 5 noise standard deviations on every line";
            if (why.empty()) ++shown;
            else dropped.push_back({{"order", order}, {"f_hz", number(fz)}, {"zeta", number(zeta)}, {"peak_in_sigmas", number(peak)}, {"reason", why}});
          }
          if (shown == modes) break;
          if (shown == 0)
            throw FitError(f.file + ": error: two-step: the FRFs from " + s.tf.input +
                           " show no vibration mode above the noise within the band");
          modes = shown;
        }
        truncate_if_short(s, deg);
        nlohmann::json j = tf_json(s);
        j["data"] = f.file;
        j["input"] = s.tf.input;
        j["source"] = "frf rational fit";
        j["order"] = s.tf.order();
        j["model_order"] = q;
        j["dropped_poles"] = dropped;
        j["fit"] = {{"sanathanan_koerner_iterations", rep.sk_iterations},
                    {"levenberg_marquardt_iterations", rep.lm_iterations},
                    {"converged", rep.converged},
                    {"reflected_poles", rep.reflected_poles},
                    {"nrmse", number(rep.nrmse)},
                    {"residual_count", rep.residual_count}};
        out.details.push_back(j);
        out.tfs.push_back(std::move(s));
      }
      continue;
    }
    const TimeRecord& t = std::get<TimeRecord>(d.content);
    std::vector<int> driven;
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      const Signal* sig = t.find(info.inputs[i]);
      if (sig && sig->values.cwiseAbs().maxCoeff() > 0) driven.push_back(static_cast<int>(i));
    }
    if (driven.size() != 1)
      throw FitError(t.file + ": error: two-step from a time record needs exactly one driven model input (one ARX "
                     "transfer function per record); this record drives " + std::to_string(driven.size()));
    std::vector<int> outputs;
    std::vector<Eigen::VectorXd> y;
    std::vector<std::string> names;
    for (std::size_t o = 0; o < info.outputs.size(); ++o)
      if (const Signal* sig = t.find(info.outputs[o])) {
        outputs.push_back(static_cast<int>(o));
        y.push_back(sig->values);
        names.push_back(info.outputs[o]);
      }
    if (outputs.empty()) throw FitError(t.file + ": error: two-step: the record holds no model output");
    StepOneTf s = structure(model, t.file, values, driven[0], outputs, candidates);
    s.overrides = overrides;
    const int q = static_cast<int>(s.pattern[0].size()) - 1;
    ArxOptions arx;
    arx.criterion = options.criterion;
    arx.max_order = options.max_arx_order;
    s.band_lo_hz = 0;
    s.band_hi_hz = arx.band_fraction / t.dt();
    const bool armax = options.model == "armax";
    const Eigen::VectorXd& u = t.at(info.inputs[static_cast<std::size_t>(driven[0])]).values;
    const std::string& input_name = info.inputs[static_cast<std::size_t>(driven[0])];
    ArxIdentification id;
    ArmaxIdentification armax_id;
    try {
      if (armax) {
        ArmaxOptions ao;
        ao.criterion = options.criterion;
        ao.extra_orders = options.armax_extra_orders;
        ao.threads = threads;
        armax_id = identify_armax(u, y, names, input_name, t.dt(), t.hold == HoldMode::None, q, degrees(s), ao, arx);
        id = armax_id.id;
      } else {
        id = identify_arx(u, y, names, input_name, t.dt(), t.hold == HoldMode::None, q, degrees(s), arx);
      }
    } catch (const std::invalid_argument& e) {
      throw FitError(t.file + ": error: two-step: " + e.what());
    }
    s.tf = id.tf;
    truncate_if_short(s, degrees(s));
    nlohmann::json j = tf_json(s);
    j["data"] = t.file;
    j["input"] = s.tf.input;
    j["source"] = armax ? "armax" : "arx";
    j["order"] = s.tf.order();
    j["model_order"] = q;
    nlohmann::json orders = nlohmann::json::array();
    for (std::size_t k = 0; k < id.orders.size(); ++k) {
      const ArxOrder& o = id.orders[k];
      nlohmann::json row = {{"order", o.order}, {"parameters", o.parameters}, {"rss", number(o.rss)},
                            {"aic", number(o.aic)}, {"bic", number(o.bic)}, {"fpe", number(o.fpe)}};
      if (armax) row.update(armax_order_json(armax_id.estimates[k], names));
      orders.push_back(row);
    }
    nlohmann::json poles = nlohmann::json::array();
    for (const ArxPole& p : id.poles)
      poles.push_back({{"f_hz", number(p.f_hz)}, {"zeta", number(p.zeta)}, {"dominance", number(p.dominance)},
                       {"nearest_zero_bandwidths", number(p.nearest_zero)}, {"kept", p.kept}, {"findings", p.findings}});
    j[armax ? "armax" : "arx"] = {{"criterion", arx.criterion},   {"selected_order", id.selected_order},
                {"hold", t.hold == HoldMode::None ? "none (first-order hold)" : "zero-order"},
                {"orders", orders},             {"poles", poles},
                {"residue_fit_nrmse", number(id.residue_nrmse)}, {"samples", id.samples}};
    out.details.push_back(j);
    out.tfs.push_back(std::move(s));
  }
  return out;
}

}  // namespace mbgen::methods
