// The `mbgen-fit/1` document (docs/interfaces.md) plus documented extra members (docs/estimation.md).
#include "mbgen/estimation/fit_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <ostream>

namespace mbgen {

namespace {

// NaN and infinities are not JSON numbers: they are written as null.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json correlation_test(const CorrelationTest& t, const char* passed, const char* failed) {
  nlohmann::json values = nlohmann::json::array();
  for (double v : t.values) values.push_back(number(v));
  return {{"lags", t.lags},       {"values", values},     {"band", number(t.band)},
          {"judged", t.judged},   {"outside", t.outside}, {"fraction_outside", number(t.fraction_outside())},
          {"allowed", t.allowed}, {"simultaneous_band", number(t.simultaneous_band)},
          {"beyond_simultaneous", t.beyond_simultaneous}, {"verdict", t.passed() ? passed : failed}};
}

nlohmann::json residual_tests_json(const FitResult& r) {
  nlohmann::json channels = nlohmann::json::array();
  for (const ChannelResidualTest& c : r.residual_tests) {
    nlohmann::json inputs = nlohmann::json::object();
    for (const auto& [name, t] : c.inputs)
      inputs[name] = correlation_test(t, "independent of the input", "correlated with the input");
    channels.push_back({{"data", c.data_set},
                        {"output", c.output},
                        {"samples", c.samples},
                        {"whiteness", correlation_test(c.whiteness, "white", "not white")},
                        {"inputs", inputs}});
  }
  return {{"max_lag", r.residual_test_lags}, {"confidence", 0.99}, {"channels", channels}};
}

nlohmann::json validation_json(const FitResult& r) {
  nlohmann::json out = nlohmann::json::array();
  for (const ValidationScore& v : r.validation) {
    nlohmann::json channels = nlohmann::json::object();
    for (const ChannelValidation& c : v.channels) channels[c.channel] = number(c.fit_percent);
    out.push_back({{"file", v.file}, {"kind", v.frf ? "frf" : "time"}, {"fit_percent", channels}});
  }
  return out;
}

}  // namespace

std::string fit_result_json(const FitResult& r) {
  nlohmann::json j;
  j["schema"] = "mbgen-fit/1";
  j["model"] = r.model;
  j["data"] = r.data;
  j["method"] = r.method;
  if (!r.warnings.empty()) j["warnings"] = r.warnings;
  nlohmann::json params = nlohmann::json::object();
  for (const auto& e : r.parameters) {
    nlohmann::json p;
    p["value"] = number(e.value);
    // A std only where the estimate has a covariance: identifiable, not at a bound, and a method that gives one
    // (arx-two-stage, modal and two-step from records give none: their `estimated` list is empty or lacks it).
    const bool has_std = e.identifiable && std::find(r.estimated.begin(), r.estimated.end(), e.name) != r.estimated.end();
    p["std"] = has_std ? number(e.std) : nlohmann::json(nullptr);
    p["identifiable"] = e.identifiable;
    p["prior"] = number(e.prior);
    p["unit"] = e.unit;
    if (!e.confounded_with.empty()) p["confounded_with"] = e.confounded_with;
    if (!e.at_bound.empty()) {
      p["at_bound"] = e.at_bound;
      p["pull_chi2"] = number(e.pull_chi2);  // how hard the data press it there (docs/estimation.md)
    }
    params[e.name] = p;
  }
  j["parameters"] = params;
  nlohmann::json f;
  f["nrmse"] = number(r.nrmse);
  f["bic"] = number(r.bic);
  f["cost"] = number(r.cost);
  f["initial_cost"] = number(r.initial_cost);
  f["residual_count"] = r.residual_count;
  f["residual_variance"] = number(r.residual_variance);
  f["iterations"] = r.iterations;
  f["converged"] = r.converged;
  f["stop_reason"] = r.stop_reason;
  f["starts"] = r.start_costs.size();
  f["best_start"] = r.best_start;
  f["seed"] = r.seed;
  j["fit"] = f;
  nlohmann::json corr = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index k = 0; k < r.correlation.cols(); ++k) row.push_back(number(r.correlation(i, k)));
    corr.push_back(row);
  }
  j["correlation"] = {{"parameters", r.estimated}, {"matrix", corr}};
  nlohmann::json sv = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.singular_values.size(); ++i) sv.push_back(number(r.singular_values[i]));
  j["singular_values"] = sv;
  nlohmann::json modes = nlohmann::json::array();
  for (const auto& m : r.modes) modes.push_back({{"f_hz", number(m.f_hz)}, {"zeta", number(m.zeta)}});
  j["modes"] = modes;
  nlohmann::json history = nlohmann::json::array();
  for (double c : r.cost_history) history.push_back(number(c));
  j["cost_history"] = history;
  if (!r.method_details.empty()) {
    nlohmann::json details = nlohmann::json::object();
    for (const auto& [name, text] : r.method_details) details[name] = nlohmann::json::parse(text);
    j["method_details"] = details;
  }
  if (!r.residual_tests.empty()) j["residual_tests"] = residual_tests_json(r);
  if (!r.validation.empty()) j["validation"] = validation_json(r);
  // Invalid UTF-8 (a file name in another encoding) cannot be JSON text: such bytes become U+FFFD.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void write_fit_json(std::ostream& out, const FitResult& result) { out << fit_result_json(result); }

}  // namespace mbgen
