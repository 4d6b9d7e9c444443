// The `mbgen-sensitivity/1` document (docs/sensitivity.md).
#include "mbgen/sensitivity/sensitivity_report.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace mbgen {

namespace {

using nlohmann::json;

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json vector_of(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number(v[i]));
  return out;
}

json indices(const SobolIndices& s, Eigen::Index mode, const std::vector<ParameterRange>& ranges) {
  json first = json::object(), total = json::object(), first_std = json::object(), total_std = json::object();
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const Eigen::Index k = static_cast<Eigen::Index>(i);
    first[ranges[i].name] = number(s.first(mode, k));
    total[ranges[i].name] = number(s.total(mode, k));
    first_std[ranges[i].name] = number(s.first_std(mode, k));
    total_std[ranges[i].name] = number(s.total_std(mode, k));
  }
  return {{"first", first},
          {"total", total},
          {"first_std", first_std},
          {"total_std", total_std},
          {"mean", number(s.mean[mode])},
          {"variance", number(s.variance[mode])},
          {"samples_used", s.used[mode]}};
}

}  // namespace

std::string sensitivity_json(const SensitivityReportInput& in) {
  const LocalSensitivity& l = in.local;
  json j;
  j["schema"] = "mbgen-sensitivity/1";
  j["model"] = in.model_file;
  json parameters = json::array();
  for (std::size_t k = 0; k < in.info.parameters.size(); ++k)
    parameters.push_back({{"name", in.info.parameters[k].name},
                          {"value", number(l.values[static_cast<Eigen::Index>(k)])},
                          {"unit", in.info.parameters[k].unit}});
  j["parameters"] = parameters;
  json modes = json::array();
  for (std::size_t r = 0; r < l.modes.size(); ++r) {
    const Eigen::Index ri = static_cast<Eigen::Index>(r);
    json sens = json::object();
    for (std::size_t k = 0; k < l.parameters.size(); ++k) {
      const Eigen::Index ki = static_cast<Eigen::Index>(k);
      sens[l.parameters[k]] = {{"f", number(l.f_normalized(ri, ki))},
                               {"zeta", number(l.zeta_normalized(ri, ki))},
                               {"df_dp", number(l.df_dp(ri, ki))},
                               {"dzeta_dp", number(l.dzeta_dp(ri, ki))}};
    }
    json visibility = json::object();
    for (std::size_t c = 0; c < in.visibility.channels.size(); ++c)
      visibility[in.visibility.channels[c]] = {
          {"dominance", number(in.visibility.dominance(ri, static_cast<Eigen::Index>(c)))},
          {"peak", number(in.visibility.peak(ri, static_cast<Eigen::Index>(c)))}};
    json mode = {{"f_hz", number(l.modes[r].f_hz)},
                 {"zeta", number(l.modes[r].zeta)},
                 {"sensitivity", sens},
                 {"visibility", visibility},
                 {"best_channel", in.visibility.channels.empty()
                                      ? json(nullptr)
                                      : json(in.visibility.channels[static_cast<std::size_t>(in.visibility.best[r])])}};
    modes.push_back(mode);
  }
  j["modes"] = modes;
  if (in.global) {
    const GlobalSensitivity& g = *in.global;
    json ranges = json::array();
    for (const ParameterRange& r : g.ranges)
      ranges.push_back({{"name", r.name}, {"lo", number(r.lo)}, {"hi", number(r.hi)}});
    json gm = json::array();
    for (std::size_t r = 0; r < g.nominal.size(); ++r)
      gm.push_back({{"f_hz", number(g.nominal[r].f_hz)},
                    {"f", indices(g.f, static_cast<Eigen::Index>(r), g.ranges)},
                    {"zeta", indices(g.zeta, static_cast<Eigen::Index>(r), g.ranges)}});
    j["global"] = {{"samples", in.sobol.samples},    {"seed", in.sobol.seed},
                   {"evaluations", g.f.evaluations}, {"ranges", ranges},
                   {"ranges_from", in.range_text},   {"modes", gm}};
  }
  json maps = json::array();
  for (const FeatureMap& m : in.maps) {
    json traces = json::array();
    for (Eigen::Index t = 0; t < m.f_hz.cols(); ++t)
      traces.push_back({{"start_f_hz", number(m.start[static_cast<std::size_t>(t)].f_hz)},
                        {"f_hz", vector_of(m.f_hz.col(t))},
                        {"zeta", vector_of(m.zeta.col(t))}});
    maps.push_back({{"parameter", m.parameter}, {"values", vector_of(m.values)}, {"traces", traces}});
  }
  j["feature_maps"] = maps;
  // Invalid UTF-8 in a file name becomes U+FFFD (docs/cli.md), not an exception.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen
