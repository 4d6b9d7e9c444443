// The report directory of `monitor`: report.md and report.html with the changes, the series, and trend plots
// drawn by gnuplot.
#include "mbgen/monitoring/monitor_report.hpp"

#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/report_document.hpp"
#include "mbgen/report/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mbgen {

namespace {

namespace fs = std::filesystem;

// The changes as dashed vertical lines, so that every trend shows where they were detected.
std::string change_marks(const MonitorResult& r) {
  std::ostringstream gp;
  for (const MonitorChange& c : r.changes)
    gp << "set arrow from " << c.index << ", graph 0 to " << c.index << ", graph 1 nohead lc rgb '"
       << (c.structural ? "#9467bd" : "#d62728") << "' dt 2\n";
  return gp.str();
}

std::string trend_script(const std::string& stem, const std::string& title, const std::string& ylabel,
                         const MonitorResult& r) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,400 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title) << " noenhanced\n"
     << "set xlabel 'data set (time order)'\nset ylabel " << gnuplot_string(ylabel) << " noenhanced\n"
     << "set grid\nset key outside right\nset xrange [-0.5:" << r.series.size() - 0.5 << "]\nset xtics 1\n"
     << change_marks(r)
     // Per set a box over its own reference band and a bar at its level: the reference changes only at the sets
     // after a change, and lines between sets would draw slopes that are not there.
     << "plot '" << stem << ".dat' using 1:4:($1-0.5):($1+0.5):5:6 with boxxyerror fs solid 0.6 noborder "
     << "fc rgb '#c6dbef' title 'reference +-2 sigma', \\\n"
     << "     '' using ($1-0.5):4:(1):(0) with vectors nohead lc rgb '#1f77b4' title 'reference', \\\n"
     << "     '' using 1:2:(2*$3) with yerrorbars pt 7 ps 0.5 lc rgb '#333333' title 'estimate +-2 std'\n";
  return gp.str();
}

std::string misfit_script(const std::string& stem, const MonitorResult& r) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,400 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set title 'misfit of each data set' noenhanced\n"
     << "set xlabel 'data set (time order)'\nset ylabel 'misfit'\nset logscale y\n"
     << "set grid\nset key outside right\nset xrange [-0.5:" << r.series.size() - 0.5 << "]\nset xtics 1\n"
     << change_marks(r)
     << "plot '" << stem << ".dat' using 1:2 with linespoints pt 7 ps 0.5 lc rgb '#333333' title 'misfit', \\\n"
     << "     '' using 1:3 with lines lc rgb '#9467bd' dt 2 title 'structural threshold'\n";
  return gp.str();
}

// The feature map (thesis Fig. 5.34): each mode's frequency against its damping ratio, one panel per mode, the
// data sets' estimates joined in time order and labelled with their index. A change of a parameter moves the points
// along the direction its sensitivity gives (`mbgen sensitivity --sweep` draws those traces).
std::string feature_map_script(const std::string& stem, std::size_t modes) {
  std::ostringstream gp;
  gp << "set terminal svg size " << std::max<std::size_t>(450, 420 * modes) << ",420 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set multiplot layout 1," << modes << " title 'modes at each estimate: frequency against damping ratio' "
     << "noenhanced\nset grid\nset xlabel 'f [Hz]'\nset ylabel 'zeta'\nset format y '%.2e'\n"
     << "set format x '%.4g'\nset xtics rotate by 30 right\n"
     << "do for [m=0:" << modes - 1 << "] {\n"
     << "  set title sprintf('mode %d', m + 1)\n"
     << "  plot '" << stem << ".dat' index m using 2:3 with linespoints pt 7 ps 0.5 lc rgb '#1f77b4' notitle, \\\n"
     << "       '' index m using 2:3:1 with labels offset 0.7,0.7 font ',8' notitle\n"
     << "}\nunset multiplot\n";
  return gp.str();
}

}  // namespace

void write_monitor_report(const std::string& dir, const MonitorResult& r) {
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw FitError("cannot create report directory " + dir + ": " + ec.message());

  report::Document doc;
  doc.heading(1, report::Inline("Monitoring report: ") << report::code(r.model));
  doc.paragraph(report::Inline() << r.series.size() << " data sets in time order; the first " << r.baseline
                                 << " are the baseline. Changes are detected by a two-sided CUSUM per parameter on its "
                                    "standardized shift (k = "
                                 << report_number(r.k, 3) << ", h = " << report_number(r.h, 4)
                                 << ": one false alarm in " << report_number(r.run_length, 6)
                                 << " data sets on average over all " << r.parameters.size()
                                 << " parameters); a data set whose misfit exceeds "
                                 << report_number(r.structural_ratio, 3) << " times the baseline's largest ("
                                 << report_number(r.baseline_misfit, 4) << ") is a structural change.");
  doc.heading(2, "Changes");
  if (r.changes.empty()) doc.paragraph("None.");
  std::vector<report::Inline> changes;
  for (const MonitorChange& c : r.changes) {
    report::Inline& line = changes.emplace_back(report::Inline("**data set ") << c.index << "**");
    if (c.time) line << " (" << report::text(*c.time) << ")";
    line << (c.structural ? ", structural" : "") << ": " << report::text(c.text);
    if (c.structural) {
      line << " Cause: " << (c.cause.empty() ? report::Inline("not found") : report::Inline(report::code(c.cause)))
           << ".";
      if (!c.qualified.empty()) {
        line << " Candidates that qualified but were not confirmed:";
        for (const std::string& q : c.qualified) line << " " << report::code(q);
        line << ".";
      }
    }
  }
  doc.list(std::move(changes));
  doc.heading(2, "Baseline");
  report::Table baseline{{"parameter", "mean", "sigma", "spread of the sets", "fits' std", "unit"}, {}};
  for (const MonitoredParameter& p : r.parameters)
    baseline.rows.push_back({report::text(p.name), report_number(p.mean), report_number(p.sigma, 3),
                             report_number(p.sample_std, 3), report_number(p.fit_std, 3), report::text(p.unit)});
  doc.table(std::move(baseline));
  doc.heading(2, "Data sets");
  report::Table sets{{"#", "data", "time", "nrmse", "misfit", "starts"}, {}};
  for (std::size_t i = 0; i < r.series.size(); ++i) {
    const MonitorPoint& s = r.series[i];
    sets.rows.push_back({report::Inline() << i << (s.baseline ? " (baseline)" : ""), report::code(s.file),
                         s.time ? report::Inline(report::text(*s.time)) : report::Inline("—"),
                         report_number(s.fit.nrmse, 4), report_number(s.misfit, 4),
                         report::Inline() << s.fit.start_costs.size()});
  }
  doc.table(std::move(sets));
  // A parameter the fit of a set pressed against a bound has no estimate there (its value is the bound, without a
  // std): it is left out of that set's trend and of the change test, and said so here.
  std::vector<report::Inline> at_bound;
  for (std::size_t i = 0; i < r.series.size(); ++i)
    for (const ParameterEstimate& e : r.series[i].fit.parameters)
      if (!e.at_bound.empty())
        at_bound.push_back(report::Inline("data set ") << i << ": " << report::code(e.name) << " at its " << e.at_bound
                                                       << " bound (" << report_number(e.value) << ")");
  if (!at_bound.empty()) {
    doc.paragraph("Parameters at a bound (value the bound, no std; not in the trends or the change test there):");
    doc.list(std::move(at_bound));
  }
  doc.heading(2, "Trends");
  doc.paragraph("Each estimate with its 2-std bar; the reference level the test compares with (the baseline's "
                "mean, re-learned after each change) with a band of 2 sigma of the scatter the baseline showed; dashed "
                "lines mark the changes (red: parameters, purple: structural).");

  std::vector<std::string> scripts;
  for (const MonitoredParameter& p : r.parameters) {
    const std::string stem = "trend_" + file_stem(p.name);
    std::ostringstream dat;
    dat << std::setprecision(10) << "# set value std reference reference-2sigma reference+2sigma\n";
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      const MonitorPoint& s = r.series[i];
      double value = std::nan(""), sd = std::nan("");
      for (const ParameterEstimate& e : s.fit.parameters)
        if (e.name == p.name && e.identifiable) {
          value = e.value;
          sd = e.std;
        }
      const auto ref = s.reference.find(p.name);
      const double level = ref != s.reference.end() ? ref->second : p.mean;
      dat << i << ' ' << value << ' ' << sd << ' ' << level << ' ' << level - 2 * p.sigma << ' ' << level + 2 * p.sigma
          << '\n';
    }
    write_report_file(root / (stem + ".dat"), dat.str());
    write_report_file(root / (stem + ".gp"),
               trend_script(stem, p.name, p.unit.empty() ? p.name : p.name + " [" + p.unit + "]", r));
    scripts.push_back(stem);
    doc.figure(stem + ".svg", report::text(p.name));
  }
  {
    std::ostringstream dat;
    dat << std::setprecision(10) << "# set misfit threshold\n";
    for (std::size_t i = 0; i < r.series.size(); ++i)
      dat << i << ' ' << r.series[i].misfit << ' ' << r.structural_ratio * r.baseline_misfit << '\n';
    write_report_file(root / "misfit.dat", dat.str());
    write_report_file(root / "misfit.gp", misfit_script("misfit", r));
    scripts.push_back("misfit");
    doc.figure("misfit.svg", "misfit");
  }
  // The feature map, for the modes every data set's estimate has (their number can differ when a mode turns
  // overdamped).
  std::size_t modes = r.series.empty() ? 0 : r.series.front().fit.modes.size();
  for (const MonitorPoint& s : r.series) modes = std::min(modes, s.fit.modes.size());
  if (modes > 0) {
    std::ostringstream dat;
    dat << std::setprecision(10) << "# per mode (gnuplot index): set f_hz zeta\n";
    for (std::size_t m = 0; m < modes; ++m) {
      if (m > 0) dat << "\n\n";
      for (std::size_t i = 0; i < r.series.size(); ++i)
        dat << i << ' ' << r.series[i].fit.modes[m].f_hz << ' ' << r.series[i].fit.modes[m].zeta << '\n';
    }
    write_report_file(root / "feature_map.dat", dat.str());
    write_report_file(root / "feature_map.gp", feature_map_script("feature_map", modes));
    scripts.push_back("feature_map");
    doc.heading(2, "Feature map");
    doc.paragraph("Each mode of the model at each data set's estimate, frequency against damping ratio, labelled "
                  "with the data set's index.");
    doc.figure("feature_map.svg", "feature map");
  }
  report::write_report(root.string(), std::move(doc), scripts);
}

}  // namespace mbgen
