// JSON, summary and report of `monitor --output-only` (runtime/include/mbgen/monitoring/operational_report.hpp).
#include "mbgen/monitoring/operational_report.hpp"

#include "mbgen/estimation/fit.hpp"
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/report_document.hpp"
#include "mbgen/report/report_files.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace mbgen {

namespace {

namespace fs = std::filesystem;

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json numbers(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}

std::string limit_distribution(const OperationalMonitorResult& r) {
  std::ostringstream s;
  s << "nu p / (nu - p + 1) F(p, nu - p + 1), p = " << r.features << ", nu = " << r.dof;
  return s.str();
}

nlohmann::json explanation_json(const ChangeExplanation& e) {
  nlohmann::json params = nlohmann::json::array();
  for (const ParameterExplanation& p : e.parameters)
    params.push_back({{"name", p.name}, {"relative_change", number(p.relative_change)}, {"chi2", number(p.chi2)},
                      {"consistent", p.consistent}, {"plausible", p.plausible}});
  return {{"dof", e.dof}, {"chi2_limit", number(e.chi2_limit)}, {"parameters", params}, {"named", e.named},
          {"text", e.text}};
}

// A change's text, with the model's explanation when there is one.
std::string change_text(const OperationalReportInput& in, std::size_t k) {
  std::string text = in.result.changes[k].text;
  if (k < in.explanations.size()) text += "; " + in.explanations[k].text;
  return text;
}

}  // namespace

std::string operational_monitor_json(const OperationalReportInput& in) {
  const OperationalMonitorResult& r = in.result;
  nlohmann::json j;
  j["schema"] = "mbgen-monitor-operational/1";
  j["method"] = in.method;
  j["channels"] = in.channels;
  j["conditions"] = r.conditions;
  nlohmann::json base;
  base["sets"] = r.baseline;
  base["compensation"] = compensation_name(r.compensation);
  base["environmental_components"] = r.environmental_components;
  base["component_variance"] = numbers(r.component_variance);
  nlohmann::json effects = nlohmann::json::array();
  for (const std::vector<double>& e : r.effects) effects.push_back(numbers(e));
  base["effects"] = effects;
  base["residual_std_hz"] = numbers(r.residual_std_hz);
  j["baseline"] = base;
  j["detector"] = {{"statistic", "Hotelling T^2"},
                   {"false_alarm", number(r.false_alarm)},
                   {"features", r.features},
                   {"dof", r.dof},
                   {"limit", number(r.limit)},
                   {"limit_distribution", limit_distribution(r)},
                   {"mode_limit", number(r.mode_limit)}};
  if (in.uncompensated)
    j["uncompensated"] = {{"limit", number(in.uncompensated->limit)},
                          {"dof", in.uncompensated->dof},
                          {"alarms", [&] {
                             std::vector<int> a;
                             for (std::size_t i = 0; i < in.uncompensated->series.size(); ++i)
                               if (in.uncompensated->series[i].alarm) a.push_back(static_cast<int>(i));
                             return a;
                           }()}};
  nlohmann::json modes = nlohmann::json::array();
  for (const TrackedMode& m : r.modes) {
    nlohmann::json shape = nlohmann::json::array();
    for (Eigen::Index k = 0; k < m.shape.size(); ++k) shape.push_back({number(m.shape[k].real()), number(m.shape[k].imag())});
    modes.push_back({{"f_hz", number(m.f_hz)}, {"zeta", number(m.zeta)}, {"f_std_hz", number(m.f_std_hz)},
                     {"shape", shape}});
  }
  j["modes"] = modes;
  nlohmann::json series = nlohmann::json::array();
  for (std::size_t i = 0; i < r.series.size(); ++i) {
    const OperationalPoint& s = r.series[i];
    nlohmann::json item;
    item["data"] = s.file;
    item["time"] = s.time ? nlohmann::json(*s.time) : nlohmann::json(nullptr);
    item["baseline"] = s.baseline;
    nlohmann::json conditions = nlohmann::json::object();
    for (std::size_t k = 0; k < r.conditions.size(); ++k) conditions[r.conditions[k]] = number(s.conditions[k]);
    item["conditions"] = conditions;
    item["identified"] = s.identified;
    nlohmann::json tracked = nlohmann::json::array();
    for (std::size_t m = 0; m < s.f_hz.size(); ++m)
      tracked.push_back({{"f_hz", number(s.f_hz[m])}, {"zeta", number(s.zeta[m])}, {"mac", number(s.mac[m])},
                         {"compensated_hz", number(s.compensated_hz[m])}, {"shift_percent", number(s.shift_percent[m])},
                         {"shift_sigma", number(s.shift_sigma[m])}});
    item["modes"] = tracked;
    item["leverage"] = number(s.leverage);
    item["t2"] = number(s.t2);
    item["alarm"] = s.alarm;
    if (in.uncompensated) item["t2_uncompensated"] = number(in.uncompensated->series[i].t2);
    series.push_back(item);
  }
  j["series"] = series;
  nlohmann::json changes = nlohmann::json::array();
  for (std::size_t k = 0; k < r.changes.size(); ++k) {
    const OperationalChange& c = r.changes[k];
    nlohmann::json item = {{"index", c.index},           {"last", c.last},
                           {"modes", c.modes},           {"shift_percent", numbers(c.shift_percent)},
                           {"shift_sigma", numbers(c.shift_sigma)}, {"text", c.text}};
    if (k < in.explanations.size()) item["explanation"] = explanation_json(in.explanations[k]);
    changes.push_back(item);
  }
  j["changes"] = changes;
  if (in.model_modes) {
    nlohmann::json pairing = nlohmann::json::array();
    for (std::size_t m = 0; m < in.model_modes->model_mode.size(); ++m)
      pairing.push_back({{"model_mode", in.model_modes->model_mode[m] >= 0 ? nlohmann::json(in.model_modes->model_mode[m])
                                                                           : nlohmann::json(nullptr)},
                         {"mac", number(in.model_modes->mac[m])},
                         {"f_hz", number(in.model_modes->f_hz[m])}});
    j["model"] = {{"file", in.model}, {"modes", pairing}};
  } else {
    j["model"] = nullptr;
  }
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string operational_monitor_summary(const OperationalReportInput& in) {
  const OperationalMonitorResult& r = in.result;
  char line[320];
  std::snprintf(line, sizeof line,
                "%zu data sets, baseline %d; %zu tracked modes; compensation: %s; Hotelling T^2 limit %.4g "
                "(false-alarm probability %.3g per set, p = %d, nu = %d)\n",
                r.series.size(), r.baseline, r.modes.size(), compensation_name(r.compensation), r.limit,
                r.false_alarm, r.features, r.dof);
  std::string out = line;
  if (r.changes.empty()) out += "no change detected\n";
  for (std::size_t k = 0; k < r.changes.size(); ++k)
    out += "change at data set " + std::to_string(r.changes[k].index) + ": " + change_text(in, k) + "\n";
  return out;
}

namespace {

std::string change_marks(const OperationalMonitorResult& r) {
  std::ostringstream gp;
  gp << "set arrow from " << r.baseline - 0.5 << ", graph 0 to " << r.baseline - 0.5
     << ", graph 1 nohead lc rgb '#7f7f7f' dt 3\n";
  for (const OperationalChange& c : r.changes)
    gp << "set arrow from " << c.index << ", graph 0 to " << c.index << ", graph 1 nohead lc rgb '#d62728' dt 2\n";
  return gp.str();
}

std::string header(const std::string& stem, const std::string& size) {
  return "set terminal svg size " + size + " dynamic font 'sans,11'\nset output '" + stem + ".svg'\n";
}

}  // namespace

void write_operational_monitor_report(const std::string& dir, const OperationalReportInput& in) {
  const OperationalMonitorResult& r = in.result;
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw FitError("cannot create report directory " + dir + ": " + ec.message());
  const std::size_t n = r.series.size(), p = r.modes.size();
  const std::string xr = "set xrange [-0.5:" + std::to_string(n) + "]\n";

  report::Document doc;
  doc.heading(1, "Monitoring in operation (output-only)");
  doc.paragraph(report::Inline() << n << " data sets in order; the first " << r.baseline
                                 << " are the baseline. Modes identified by " << report::text(in.method)
                                 << " and tracked by MAC with the first set's; their frequencies' dependence on the "
                                    "conditions is removed by "
                                 << compensation_name(r.compensation)
                                 << (r.compensation == Compensation::PrincipalComponents
                                         ? " (" + std::to_string(r.environmental_components) +
                                               " leading component(s) taken as environmental)"
                                         : std::string())
                                 << ". Each set's Hotelling T^2 is compared with the limit "
                                 << report_number(r.limit, 4) << ": a set without a change exceeds it with probability "
                                 << report_number(r.false_alarm, 3) << " (" << report::text(limit_distribution(r))
                                 << ").");
  doc.heading(2, "Changes");
  std::vector<report::Inline> changes;
  for (std::size_t k = 0; k < r.changes.size(); ++k)
    changes.emplace_back(report::Inline("**data set ") << r.changes[k].index << "**: "
                                                      << report::text(change_text(in, k)));
  if (changes.empty()) doc.paragraph("None.");
  doc.list(std::move(changes));
  if (in.uncompensated) {
    std::size_t alarms = 0, before = 0;
    const int first = r.changes.empty() ? static_cast<int>(n) : r.changes.front().index;
    for (std::size_t i = 0; i < n; ++i)
      if (in.uncompensated->series[i].alarm) {
        ++alarms;
        if (static_cast<int>(i) < first) ++before;
      }
    doc.paragraph(report::Inline("Without compensation (the raw frequencies against the baseline's mean and "
                                 "covariance, limit ")
                  << report_number(in.uncompensated->limit, 4) << ") " << alarms << " sets would alarm, " << before
                  << " of them before the first change found with compensation.");
  }
  doc.heading(2, "Tracked modes");
  report::Table modes{{"mode", "f [Hz]", "zeta", "spread [Hz]", "residual std [Hz]", "effects"}, {}};
  for (std::size_t j = 0; j < p; ++j) {
    report::Inline effect;
    if (r.compensation == Compensation::Regression)
      for (std::size_t k = 0; k < r.conditions.size(); ++k)
        effect << (k ? ", " : "") << report_number(r.effects[j][k], 4) << " Hz per " << report::text(r.conditions[k]);
    else if (r.compensation == Compensation::PrincipalComponents)
      for (std::size_t k = 0; k < r.effects.size(); ++k)
        effect << (k ? ", " : "") << "component " << (k + 1) << ": " << report_number(r.effects[k][j], 3);
    modes.rows.push_back({report::Inline() << (j + 1), report_number(r.modes[j].f_hz, 7),
                          report_number(r.modes[j].zeta, 3), report_number(r.modes[j].f_std_hz, 3),
                          report_number(r.residual_std_hz[j], 3), effect});
  }
  doc.table(std::move(modes));
  if (in.model_modes) {
    doc.paragraph(report::Inline("Model ") << report::code(in.model) << ": the tracked modes paired by MAC with its "
                                                                       "modes at the sensors.");
    report::Table pairing{{"mode", "model mode", "MAC", "model f [Hz]"}, {}};
    for (std::size_t j = 0; j < p; ++j)
      pairing.rows.push_back({report::Inline() << (j + 1),
                              in.model_modes->model_mode[j] >= 0 ? report::Inline() << (in.model_modes->model_mode[j] + 1)
                                                                 : report::Inline("—"),
                              report_number(in.model_modes->mac[j], 4), report_number(in.model_modes->f_hz[j], 6)});
    doc.table(std::move(pairing));
  }
  doc.heading(2, "Data sets");
  std::vector<report::Inline> head{"#", "data"};
  for (const std::string& c : r.conditions) head.push_back(report::text(c));
  for (std::size_t j = 0; j < p; ++j) head.push_back(report::Inline("f") << (j + 1) << " [Hz]");
  head.push_back("T^2");
  report::Table sets{head, {}};
  for (std::size_t i = 0; i < n; ++i) {
    const OperationalPoint& s = r.series[i];
    std::vector<report::Inline> row{report::Inline() << i << (s.baseline ? " (baseline)" : s.alarm ? " **alarm**" : ""),
                                    report::code(s.file)};
    for (double c : s.conditions) row.push_back(report_number(c, 5));
    for (double f : s.f_hz) row.push_back(report_number(f, 7));
    row.push_back(report_number(s.t2, 4));
    sets.rows.push_back(std::move(row));
  }
  doc.table(std::move(sets));

  std::vector<std::string> scripts;
  {
    std::ostringstream dat;
    dat << std::setprecision(10) << "# per tracked mode (gnuplot index): set f_hz compensated_hz\n";
    for (std::size_t j = 0; j < p; ++j) {
      if (j) dat << "\n\n";
      for (std::size_t i = 0; i < n; ++i)
        dat << i << ' ' << r.series[i].f_hz[j] << ' ' << r.series[i].compensated_hz[j] << '\n';
    }
    write_report_file((root / "frequencies.dat").string(), dat.str());
    std::ostringstream gp;
    gp << header("frequencies", "900," + std::to_string(260 * p + 60))
       << "set multiplot layout " << p << ",1 title 'tracked frequencies: raw and compensated' noenhanced\n"
       << "set grid\nset key outside right\nset xlabel 'data set'\nset ylabel 'f [Hz]'\nset format y '%.6g'\n" << xr
       << change_marks(r) << "do for [m=0:" << p - 1 << "] {\n  set title sprintf('mode %d', m + 1)\n"
       << "  plot 'frequencies.dat' index m using 1:2 with linespoints pt 7 ps 0.5 lc rgb '#7f7f7f' title 'raw', \\\n"
       << "       '' index m using 1:3 with linespoints pt 7 ps 0.5 lc rgb '#1f77b4' title 'compensated'\n}\n"
       << "unset multiplot\n";
    write_report_file((root / "frequencies.gp").string(), gp.str());
    scripts.push_back("frequencies");
  }
  {
    std::ostringstream dat;
    dat << std::setprecision(10) << "# set t2 limit t2_uncompensated limit_uncompensated\n";
    for (std::size_t i = 0; i < n; ++i) {
      dat << i << ' ' << r.series[i].t2 << ' ' << r.limit;
      if (in.uncompensated) dat << ' ' << in.uncompensated->series[i].t2 << ' ' << in.uncompensated->limit;
      dat << '\n';
    }
    write_report_file((root / "t2.dat").string(), dat.str());
    std::ostringstream gp;
    gp << header("t2", "900,400") << "set title 'Hotelling T^2 of each data set' noenhanced\n"
       << "set xlabel 'data set'\nset ylabel 'T^2' noenhanced\nset logscale y\nset grid\nset key outside right\n" << xr
       << change_marks(r)
       << "plot 't2.dat' using 1:2 with linespoints pt 7 ps 0.5 lc rgb '#1f77b4' title 'compensated', \\\n"
       << "     '' using 1:3 with lines lc rgb '#1f77b4' dt 2 title 'limit'";
    if (in.uncompensated)
      gp << ", \\\n     '' using 1:4 with linespoints pt 6 ps 0.5 lc rgb '#ff7f0e' title 'uncompensated', \\\n"
         << "     '' using 1:5 with lines lc rgb '#ff7f0e' dt 2 title 'its limit'";
    gp << "\n";
    write_report_file((root / "t2.gp").string(), gp.str());
    scripts.push_back("t2");
  }
  if (!r.conditions.empty()) {
    std::ostringstream dat;
    dat << std::setprecision(10) << "# per condition (gnuplot index): set value\n";
    for (std::size_t k = 0; k < r.conditions.size(); ++k) {
      if (k) dat << "\n\n";
      for (std::size_t i = 0; i < n; ++i) dat << i << ' ' << r.series[i].conditions[k] << '\n';
    }
    write_report_file((root / "conditions.dat").string(), dat.str());
    std::ostringstream gp;
    gp << header("conditions", "900," + std::to_string(220 * r.conditions.size() + 60)) << "set multiplot layout "
       << r.conditions.size() << ",1 title 'conditions' noenhanced\nset grid\nset xlabel 'data set'\n" << xr
       << change_marks(r);
    for (std::size_t k = 0; k < r.conditions.size(); ++k)
      gp << "set title " << gnuplot_string(r.conditions[k]) << " noenhanced\nplot 'conditions.dat' index " << k
         << " using 1:2 with linespoints pt 7 ps 0.5 lc rgb '#2ca02c' notitle\n";
    gp << "unset multiplot\n";
    write_report_file((root / "conditions.gp").string(), gp.str());
    scripts.push_back("conditions");
  }
  doc.heading(2, "Trends");
  doc.paragraph("The tracked frequencies, raw and with the conditions' effect removed; the T^2 chart with its limit "
                "(log scale). Dotted grey: the end of the baseline; dashed red: the changes.");
  doc.figure("frequencies.svg", "tracked frequencies");
  doc.figure("t2.svg", "T^2 chart");
  if (!r.conditions.empty()) doc.figure("conditions.svg", "conditions");
  report::write_report(root.string(), std::move(doc), scripts);
}

}  // namespace mbgen
