// The `mbgen-monitor/1` document (docs/interfaces.md) plus documented extra members (docs/monitor.md).
#include "mbgen/monitoring/monitor_report.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace mbgen {

namespace {

// NaN and infinities are not JSON numbers: they are written as null.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json optional_text(const std::optional<std::string>& s) {
  return s ? nlohmann::json(*s) : nlohmann::json(nullptr);
}

}  // namespace

std::string monitor_result_json(const MonitorResult& r) {
  nlohmann::json j;
  j["schema"] = "mbgen-monitor/1";
  j["model"] = r.model;
  if (!r.start_method.empty()) j["start_method"] = r.start_method;
  nlohmann::json base;
  base["sets"] = r.baseline;
  base["misfit"] = number(r.baseline_misfit);
  nlohmann::json monitored = nlohmann::json::object();
  for (const MonitoredParameter& p : r.parameters)
    monitored[p.name] = {{"mean", number(p.mean)}, {"sigma", number(p.sigma)}, {"sample_std", number(p.sample_std)},
                         {"fit_std", number(p.fit_std)}, {"unit", p.unit}};
  base["parameters"] = monitored;
  j["baseline"] = base;
  j["detector"] = {{"method", "two-sided CUSUM"}, {"k", number(r.k)}, {"h", number(r.h)}, {"single_set_limit", number(r.single_set_limit)},
                   {"run_length", number(r.run_length)}, {"structural_ratio", number(r.structural_ratio)}};
  nlohmann::json series = nlohmann::json::array();
  for (const MonitorPoint& s : r.series) {
    nlohmann::json item;
    item["data"] = s.file;
    item["time"] = optional_text(s.time);
    item["baseline"] = s.baseline;
    nlohmann::json params = nlohmann::json::object();
    for (const ParameterEstimate& e : s.fit.parameters) {
      if (!e.estimated) continue;
      nlohmann::json p;
      p["value"] = number(e.value);
      p["std"] = e.identifiable ? number(e.std) : nlohmann::json(nullptr);
      if (!e.at_bound.empty()) p["at_bound"] = e.at_bound;  // the value is the bound; no std (as in mbgen-fit/1)
      if (const auto z = s.shift.find(e.name); z != s.shift.end()) {
        p["shift"] = number(z->second);
        p["reference"] = number(s.reference.at(e.name));
        p["cusum_up"] = number(s.cusum_up.at(e.name));
        p["cusum_down"] = number(s.cusum_down.at(e.name));
      }
      params[e.name] = p;
    }
    item["parameters"] = params;
    item["fit"] = {{"nrmse", number(s.fit.nrmse)},
                   {"bic", number(s.fit.bic)},
                   {"residual_variance", number(s.fit.residual_variance)},
                   {"misfit", number(s.misfit)},
                   {"starts", s.fit.start_costs.size()},
                   {"converged", s.fit.converged}};
    nlohmann::json modes = nlohmann::json::array();
    for (const Mode& m : s.fit.modes) modes.push_back({{"f_hz", number(m.f_hz)}, {"zeta", number(m.zeta)}});
    item["modes"] = modes;
    series.push_back(item);
  }
  j["series"] = series;
  nlohmann::json changes = nlohmann::json::array();
  for (const MonitorChange& c : r.changes) {
    nlohmann::json item;
    item["index"] = c.index;
    item["onset"] = c.onset;
    item["time"] = optional_text(c.time);
    item["parameters"] = c.parameters;
    nlohmann::json direction = nlohmann::json::object();
    for (const auto& [name, d] : c.direction) direction[name] = d > 0 ? "up" : "down";
    item["direction"] = direction;
    item["structural"] = c.structural;
    item["misfit_ratio"] = number(c.misfit_ratio);
    item["cause"] = c.cause.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.cause);
    if (c.structural) item["qualified_candidates"] = c.qualified;
    item["text"] = c.text;
    changes.push_back(item);
  }
  j["changes"] = changes;
  // Invalid UTF-8 (a file name in another encoding) cannot be JSON text: such bytes become U+FFFD.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen
