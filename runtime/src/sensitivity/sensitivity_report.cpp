// The report directory of `mbgen sensitivity`: report.md and report.html with tables and SVG plots drawn by
// gnuplot from .dat files and .gp scripts; and the terminal summary.
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/mode_shape_figures.hpp"
#include "mbgen/report/report_document.hpp"
#include "mbgen/sensitivity/sensitivity_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

void write_file(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(path + ": error: cannot write the report");
}

std::string num(double x, int digits = 3) {
  if (!std::isfinite(x)) return "—";
  if (x == 0) x = 0;  // no "-0"
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string mode_label(const Mode& m, std::size_t r) {
  return detail::format("%zu (%.1f Hz)", r + 1, m.f_hz);
}

// Parameters ordered by the largest |normalized f sensitivity| over the modes, most influential first.
std::vector<std::size_t> by_influence(const Eigen::MatrixXd& s) {
  std::vector<std::size_t> order(static_cast<std::size_t>(s.cols()));
  std::iota(order.begin(), order.end(), 0);
  const auto weight = [&](std::size_t k) {
    return s.rows() ? s.col(static_cast<Eigen::Index>(k)).cwiseAbs().maxCoeff() : 0.0;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return weight(a) > weight(b); });
  return order;
}

void heat_map(const std::string& dir, const std::string& stem, const std::string& title, const Eigen::MatrixXd& values,
              const std::vector<std::string>& rows, const std::vector<std::string>& cols) {
  std::ostringstream dat, gp;
  dat << std::setprecision(6);
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index j = 0; j < values.cols(); ++j)
      dat << j << ' ' << i << ' ' << (std::isfinite(values(i, j)) ? values(i, j) : 0.0)
          << (j + 1 == values.cols() ? "\n\n" : "\n");
  const double limit = std::max(1e-12, values.array().isFinite().select(values.cwiseAbs(), 0).maxCoeff());
  gp << "set terminal svg size " << std::max(500, 70 * static_cast<int>(cols.size()) + 200) << ","
     << 120 + 40 * rows.size() << " dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title)
     << " noenhanced\nset palette defined (-1 '#b2182b', 0 'white', 1 '#2166ac')\n"
     << "set cbrange [" << -limit << ":" << limit << "]\nset xtics rotate by -45 noenhanced\nset ytics noenhanced\n"
     << "set xrange [-0.5:" << values.cols() - 0.5 << "]\nset yrange [" << values.rows() - 0.5 << ":-0.5]\nset xtics (";
  for (std::size_t j = 0; j < cols.size(); ++j) gp << (j ? ", " : "") << gnuplot_string(cols[j]) << " " << j;
  gp << ")\nset ytics (";
  for (std::size_t i = 0; i < rows.size(); ++i) gp << (i ? ", " : "") << gnuplot_string(rows[i]) << " " << i;
  gp << ")\nplot '" << stem << ".dat' using 1:2:3 with image notitle, '' using 1:2:(sprintf('%.2f', $3)) with labels "
     << "font ',8' notitle\n";
  write_file(dir, stem + ".dat", dat.str());
  write_file(dir, stem + ".gp", gp.str());
}

}  // namespace

std::string sensitivity_summary(const SensitivityReportInput& in) {
  const LocalSensitivity& l = in.local;
  std::ostringstream out;
  out << l.modes.size() << " modes of " << in.model_file << "; the parameters that move each most (normalized "
      << "sensitivity of f: relative change of f per relative change of the parameter):\n";
  for (std::size_t r = 0; r < l.modes.size(); ++r) {
    const Eigen::Index ri = static_cast<Eigen::Index>(r);
    std::vector<std::size_t> order(l.parameters.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return std::abs(l.f_normalized(ri, static_cast<Eigen::Index>(a))) >
             std::abs(l.f_normalized(ri, static_cast<Eigen::Index>(b)));
    });
    out << detail::format("%4zu %10.3f Hz  zeta %.4g  ", r + 1, l.modes[r].f_hz, l.modes[r].zeta);
    for (std::size_t k = 0; k < std::min<std::size_t>(3, order.size()); ++k)
      out << (k ? ", " : "") << l.parameters[order[k]] << " "
          << num(l.f_normalized(ri, static_cast<Eigen::Index>(order[k])), 3);
    if (!in.visibility.channels.empty())
      out << "; seen best at " << in.visibility.channels[static_cast<std::size_t>(in.visibility.best[r])];
    out << "\n";
  }
  if (in.global) {
    out << "Sobol total indices of f (" << in.global->f.evaluations << " modal analyses; those of 0.01 or more):\n";
    for (std::size_t r = 0; r < in.global->nominal.size(); ++r) {
      const Eigen::RowVectorXd st = in.global->f.total.row(static_cast<Eigen::Index>(r));
      std::vector<std::size_t> order(in.global->ranges.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return st[static_cast<Eigen::Index>(a)] > st[static_cast<Eigen::Index>(b)];
      });
      out << "  mode " << r + 1 << ":";
      for (std::size_t i : order)
        if (st[static_cast<Eigen::Index>(i)] >= 0.01)
          out << " " << in.global->ranges[i].name << " " << num(st[static_cast<Eigen::Index>(i)], 2);
      out << "\n";
    }
  }
  for (const FeatureMap& m : in.maps)
    out << "feature map: " << m.parameter << " from " << num(m.values[0], 6) << " to "
        << num(m.values[m.values.size() - 1], 6) << ", " << m.values.size() << " points, " << m.f_hz.cols()
        << " traces\n";
  return out.str();
}

void write_sensitivity_report(const std::string& dir, const SensitivityReportInput& in) {
  const LocalSensitivity& l = in.local;
  std::vector<std::string> stems, mode_labels;
  for (std::size_t r = 0; r < l.modes.size(); ++r) mode_labels.push_back(mode_label(l.modes[r], r));
  report::Document doc;
  doc.heading(1, report::Inline("Sensitivity of the modes of ") << report::code(in.model_file));
  report::Inline values = "At the parameter values:";
  for (std::size_t k = 0; k < l.parameters.size(); ++k)
    values << (k ? ", " : " ") << "`" << l.parameters[k] << "` = " << num(l.values[static_cast<Eigen::Index>(k)], 6);
  doc.paragraph(values << ".");
  doc.heading(2, "Modes and their local sensitivities");
  doc.paragraph("Normalized sensitivities `(p/f) df/dp` and `(p/zeta) dzeta/dp`: the relative change of a mode's "
                "frequency or damping ratio per relative change of a parameter (first-order eigenvalue perturbation, "
                "exact). Scaling all of M, C and K together changes nothing, so each row of a model whose parameters "
                "are all mass, damping and stiffness coefficients sums to 0. Parameters ordered by influence on the "
                "frequencies.");
  const std::vector<std::size_t> order = by_influence(l.f_normalized);
  std::vector<std::string> ordered_names;
  for (std::size_t k : order) ordered_names.push_back(l.parameters[k]);
  for (const bool zeta : {false, true}) {
    const Eigen::MatrixXd& s = zeta ? l.zeta_normalized : l.f_normalized;
    doc.heading(3, zeta ? "Damping ratio" : "Frequency");
    report::Table table{{"mode", "f [Hz]", "zeta"}, {}};
    for (const std::string& n : ordered_names) table.header.push_back("`" + n + "`");
    Eigen::MatrixXd shown(s.rows(), static_cast<Eigen::Index>(order.size()));
    for (std::size_t r = 0; r < l.modes.size(); ++r) {
      std::vector<report::Inline>& row =
          table.rows.emplace_back(std::vector<report::Inline>{report::Inline() << r + 1, num(l.modes[r].f_hz, 6),
                                                              num(l.modes[r].zeta, 4)});
      for (std::size_t k = 0; k < order.size(); ++k) {
        const double v = s(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(order[k]));
        shown(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = v;
        row.push_back(num(v));
      }
    }
    doc.table(std::move(table));
    const std::string stem = zeta ? "local_zeta" : "local_f";
    heat_map(dir, stem, zeta ? "(p/zeta) dzeta/dp" : "(p/f) df/dp", shown, mode_labels, ordered_names);
    stems.push_back(stem);
    doc.figure(stem + ".svg", stem);
  }

  doc.heading(2, "Which channel sees each mode best");
  doc.paragraph("Dominance: the mode's share of the channel's response at the mode's frequency, |modal term| / |H| "
                "(exact partial fractions). A sensor where one mode dominates separates it best from its "
                "neighbours.");
  report::Table visibility{{"mode"}, {}};
  for (const std::string& c : in.visibility.channels) visibility.header.push_back(report::code(c));
  visibility.header.push_back("best");
  for (std::size_t r = 0; r < l.modes.size(); ++r) {
    std::vector<report::Inline>& row = visibility.rows.emplace_back(1, mode_labels[r]);
    for (std::size_t c = 0; c < in.visibility.channels.size(); ++c)
      row.push_back(num(in.visibility.dominance(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)), 4));
    row.push_back(report::code(in.visibility.channels.empty()
                                   ? ""
                                   : in.visibility.channels[static_cast<std::size_t>(in.visibility.best[r])]));
  }
  doc.table(std::move(visibility));

  if (in.geometry && !l.modes.empty()) {
    doc.heading(2, "Mode shapes");
    doc.paragraph(mode_shape_legend());
    std::vector<std::string> titles;
    Eigen::MatrixXcd shapes(l.modes.front().shape.size(), static_cast<Eigen::Index>(l.modes.size()));
    for (std::size_t r = 0; r < l.modes.size(); ++r) {
      titles.push_back(mode_title("mode " + std::to_string(r + 1), l.modes[r].f_hz, l.modes[r].zeta));
      shapes.col(static_cast<Eigen::Index>(r)) = l.modes[r].shape;
    }
    add_model_mode_figures(doc, dir, "mode_shape", *in.geometry, titles, shapes);
  }

  if (in.global) {
    const GlobalSensitivity& g = *in.global;
    doc.heading(2, "Global sensitivity: Sobol indices");
    doc.paragraph("Parameters uniform over " + in.range_text + ":");
    report::Table ranges{{"parameter", "from", "to"}, {}};
    for (const ParameterRange& r : g.ranges) ranges.rows.push_back({"`" + r.name + "`", num(r.lo, 6), num(r.hi, 6)});
    doc.table(std::move(ranges));
    doc.paragraph(report::Inline("First-order indices S (Saltelli 2010) and total indices ST (Jansen), N = ")
                  << in.sobol.samples << ", seed " << in.sobol.seed << ", " << g.f.evaluations
                  << " modal analyses; +- one standard error. ST - S is what a parameter does through interactions; "
                     "sum of S near 1 means an additive model.");
    std::vector<std::string> names;
    for (const ParameterRange& r : g.ranges) names.push_back(r.name);
    for (const bool zeta : {false, true}) {
      const SobolIndices& s = zeta ? g.zeta : g.f;
      doc.heading(3, zeta ? "Damping ratio" : "Frequency");
      report::Table table{{"mode", zeta ? "std of zeta" : "std of f [Hz]"}, {}};
      for (const std::string& n : names) table.header.push_back("`" + n + "` S / ST");
      for (std::size_t r = 0; r < g.nominal.size(); ++r) {
        const Eigen::Index ri = static_cast<Eigen::Index>(r);
        std::vector<report::Inline>& row = table.rows.emplace_back(
            std::vector<report::Inline>{mode_label(g.nominal[r], r), num(std::sqrt(s.variance[ri]), 3)});
        for (std::size_t k = 0; k < names.size(); ++k) {
          const Eigen::Index ki = static_cast<Eigen::Index>(k);
          row.push_back(num(s.first(ri, ki), 2) + " +- " + num(s.first_std(ri, ki), 1) + " / " +
                        num(s.total(ri, ki), 2) + " +- " + num(s.total_std(ri, ki), 1));
        }
      }
      doc.table(std::move(table));
      const std::string stem = zeta ? "sobol_zeta" : "sobol_f";
      heat_map(
          dir, stem, zeta ? "total Sobol indices of zeta" : "total Sobol indices of f", s.total,
          [&] {
            std::vector<std::string> labels;
            for (std::size_t r = 0; r < g.nominal.size(); ++r) labels.push_back(mode_label(g.nominal[r], r));
            return labels;
          }(),
          names);
      stems.push_back(stem);
      doc.figure(stem + ".svg", stem);
    }
  }

  if (!in.maps.empty()) {
    doc.heading(2, "Feature maps");
    doc.paragraph("Each mode's frequency against its damping ratio as one parameter sweeps (the others at their "
                  "values); the modes are followed by MAC from step to step.");
  }
  for (std::size_t i = 0; i < in.maps.size(); ++i) {
    const FeatureMap& m = in.maps[i];
    const std::string stem = "feature_map_" + std::to_string(i + 1);
    std::ostringstream dat, gp;
    dat << std::setprecision(9) << "# per trace (blocks): " << m.parameter << " f_hz zeta\n";
    for (Eigen::Index t = 0; t < m.f_hz.cols(); ++t) {
      for (Eigen::Index k = 0; k < m.values.size(); ++k)
        if (std::isfinite(m.f_hz(k, t))) dat << m.values[k] << ' ' << m.f_hz(k, t) << ' ' << m.zeta(k, t) << '\n';
      dat << "\n\n";
    }
    gp << "set terminal svg size 900,600 dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
       << "set title "
       << gnuplot_string("feature map: " + m.parameter + " from " + num(m.values[0], 4) + " (circle) to " +
                   num(m.values[m.values.size() - 1], 4) + " (triangle)")
       << " noenhanced\nset xlabel 'f [Hz]'\nset ylabel 'zeta'\nset grid\nset key outside right top\nplot ";
    for (Eigen::Index t = 0; t < m.f_hz.cols(); ++t)
      gp << (t ? ", \\\n     " : "") << "'" << stem << ".dat' index " << t
         << " using 2:3 with linespoints pt 7 ps 0.4 lc " << t + 1 << " title "
         << gnuplot_string("mode " + mode_label(m.start[static_cast<std::size_t>(t)], static_cast<std::size_t>(t)))
         << ", '' index " << t << " every ::0::0 using 2:3 with points pt 6 ps 1.5 lc " << t + 1
         << " notitle, '' index " << t << " every ::" << m.values.size() - 1 << " using 2:3 with points pt 8 ps 1.5 lc "
         << t + 1 << " notitle";
    gp << "\n";
    write_file(dir, stem + ".dat", dat.str());
    write_file(dir, stem + ".gp", gp.str());
    stems.push_back(stem);
    doc.heading(3, m.parameter);
    doc.figure(stem + ".svg", "feature map " + m.parameter);
  }
  report::write_report(dir, std::move(doc), stems);
}

}  // namespace mbgen
