// The report directory: report.md and report.html with tables and SVG plots drawn by gnuplot from .dat files and
// .gp scripts.
#include "mbgen/estimation/fit_report.hpp"

#include "fit_report_sections.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen/estimation/frf_confidence.hpp"
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/report_document.hpp"
#include "mbgen/report/report_files.hpp"
#include "numerics/constants.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>

namespace mbgen {

namespace {

namespace fs = std::filesystem;

double phase_deg(std::complex<double> h) { return numerics::degrees(std::arg(h)); }

// `band`: the .dat has the estimate's +-2 std band of |H| in columns 10 and 11 and of the phase in 12 and 13, drawn
// light beneath the points and curves.
std::string frf_script(const std::string& stem, const std::string& title, bool band) {
  const auto band_then = [&](int lo, int hi) {
    return band ? "using 1:" + std::to_string(lo) + ":" + std::to_string(hi) +
                      " with filledcurves fs solid 0.35 noborder lc rgb '#f4a582' title 'estimate, +-2 std', \\\n     '' "
                : std::string();
  };
  std::ostringstream gp;
  gp << "set terminal svg size 900,700 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set multiplot layout 2,1 title " << gnuplot_string(title) << " noenhanced\n"
     << "set logscale y\nset format y '%.0e'\nset grid\nset ylabel '|H|'\nset key top right\n"
     << "plot '" << stem << ".dat' " << band_then(10, 11)
     << "using 1:2 with points pt 7 ps 0.3 lc rgb '#555555' title 'data', \\\n"
     << "     '' using 1:4 with lines lc rgb '#1f77b4' dt 2 title 'model, prior', \\\n"
     << "     '' using 1:6 with lines lc rgb '#d62728' title 'model, estimate'\n"
     << "unset logscale y\nset format y '%g'\nset ylabel 'phase [deg]'\nset xlabel 'f [Hz]'\nset yrange [-180:180]\nset ytics 90\n"
     << "plot '" << stem << ".dat' " << band_then(12, 13)
     << "using 1:3 with points pt 7 ps 0.3 lc rgb '#555555' title 'data', \\\n"
     << "     '' using 1:5 with lines lc rgb '#1f77b4' dt 2 title 'model, prior', \\\n"
     << "     '' using 1:7 with lines lc rgb '#d62728' title 'model, estimate'\n"
     << "unset multiplot\n"
     << "set terminal svg size 900,400 dynamic font 'sans,11'\n"
     << "set output '" << stem << "_residual.svg'\n"
     << "set title " << gnuplot_string(title + ": residual |H_model - H_data|") << " noenhanced\n"
     << "set autoscale y\nset ytics auto\nset logscale y\n"
     << "set ylabel '|residual|'\n"
     << "plot '" << stem << ".dat' using 1:8 with lines lc rgb '#1f77b4' dt 2 title 'prior', \\\n"
     << "     '' using 1:9 with lines lc rgb '#d62728' title 'estimate'\n";
  return gp.str();
}

bool has_covariance(const FitResult& r) {
  const auto k = static_cast<Eigen::Index>(r.estimated.size());
  return k > 0 && r.covariance.rows() == k && r.covariance.cols() == k && r.covariance.allFinite();
}

// The estimate's bands on the channels of FRF data set `d` (its `# set` values applied and held), one per channel,
// empty where the fit has no covariance or the model's FRF cannot be evaluated at these lines.
std::vector<std::optional<FrfBand>> estimate_bands(const Model& model, const DataSet& d, const FitResult& r) {
  const FrfData& frf = std::get<FrfData>(d.content);
  std::vector<std::optional<FrfBand>> out(frf.channels.size());
  if (!has_covariance(r)) return out;
  const ModelInfo& info = model.info();
  std::vector<std::pair<int, int>> entries;
  for (const FrfChannel& channel : frf.channels) {
    const auto output = std::find(info.outputs.begin(), info.outputs.end(), channel.output) - info.outputs.begin();
    const auto input = std::find(info.inputs.begin(), info.inputs.end(), channel.input) - info.inputs.begin();
    if (output == static_cast<long>(info.outputs.size()) || input == static_cast<long>(info.inputs.size())) return out;
    entries.emplace_back(static_cast<int>(output), static_cast<int>(input));
  }
  Eigen::VectorXd values = r.values;
  std::vector<int> held, estimated;
  for (const auto& [name, value] : d.set()) {
    const int idx = info.parameter_index(name);
    if (idx < 0) return out;
    values[idx] = value.value;
    held.push_back(idx);
  }
  for (const std::string& name : r.estimated) estimated.push_back(info.parameter_index(name));
  try {
    std::vector<FrfBand> bands = frf_bands(model, values, estimated, r.covariance,
                                           std::vector<double>(frf.f_hz.data(), frf.f_hz.data() + frf.f_hz.size()),
                                           entries, held);
    for (std::size_t c = 0; c < bands.size(); ++c) out[c] = std::move(bands[c]);
  } catch (const DynamicsError&) {
  }
  return out;
}

std::string time_script(const std::string& stem, const std::string& title) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,700 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set multiplot layout 2,1 title " << gnuplot_string(title) << " noenhanced\nset grid\nset key top right\n"
     << "set ylabel 'output'\n"
     << "plot '" << stem << ".dat' using 1:2 with lines lc rgb '#555555' title 'data', \\\n"
     << "     '' using 1:3 with lines lc rgb '#1f77b4' dt 2 title 'model, prior', \\\n"
     << "     '' using 1:4 with lines lc rgb '#d62728' title 'model, estimate'\n"
     << "set ylabel 'residual'\nset xlabel 't [s]'\n"
     << "plot '" << stem << ".dat' using 1:5 with lines lc rgb '#1f77b4' title 'prior', \\\n"
     << "     '' using 1:6 with lines lc rgb '#d62728' title 'estimate'\n"
     << "unset multiplot\n";
  return gp.str();
}

}  // namespace

void write_fit_report(const std::string& dir, const Model& model, const std::vector<DataSet>& data,
                      const FitResult& result, const std::vector<DataSet>& validation) {
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw FitError("cannot create report directory " + dir + ": " + ec.message());
  const Prediction before = predict(model, data, result.prior_values);
  const Prediction after = predict(model, data, result.values);

  report::Document doc;
  doc.heading(1, report::Inline("Fit report: ") << report::code(result.model));
  for (const std::string& w : result.warnings) doc.paragraph(report::Inline("**Warning:** ") << report::text(w) << ".");
  report::Inline intro = report::Inline("Method: `") << result.method << "`. Data:";
  for (const auto& d : result.data) intro << " " << report::code(d);
  doc.paragraph(intro << ".");
  // A method's own one-line account of what it did (method_details.NAME.summary), e.g. two-step's route.
  for (const auto& [name, text] : result.method_details) {
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.contains("summary") && j["summary"].is_string())
      doc.paragraph(report::Inline(report::code(name)) << ": " << report::text(j["summary"].get<std::string>()) << ".");
  }

  doc.heading(2, "Parameters");
  report::Table parameters{{"parameter", "prior", "estimate", "std", "relative std", "identifiable", "unit"}, {}};
  for (const auto& e : result.parameters) {
    // A std only where the method gives one (as in the JSON: the parameter has a covariance row).
    const bool has_std = e.identifiable &&
                         std::find(result.estimated.begin(), result.estimated.end(), e.name) != result.estimated.end();
    report::Inline identifiable = e.identifiable        ? "yes"
                                  : e.at_bound.empty() ? "**no** (kept at prior)"
                                                       : "**no**: at its " + e.at_bound + " bound";
    if (!e.confounded_with.empty()) {
      identifiable << "; confounded with";
      for (const auto& c : e.confounded_with) identifiable << " " << c;
    }
    parameters.rows.push_back(
        {e.name, report_number(e.prior), report_number(e.value), has_std ? report_number(e.std, 3) : "—",
         has_std && e.value != 0 ? report_number(100 * e.std / std::abs(e.value), 3) + " %" : "—", identifiable,
         report::text(e.unit)});
  }
  doc.table(std::move(parameters));

  doc.heading(2, "Fit");
  doc.list({report::Inline("residuals n = ") << result.residual_count << ", estimated parameters k = "
                                             << result.estimated.size(),
            "weighted RSS: prior " + report_number(result.initial_cost) + ", estimate " + report_number(result.cost),
            "NRMSE (sqrt of RSS over the weighted data's sum of squares) = " + report_number(result.nrmse, 4),
            "BIC = n log(RSS/n) + k log n = " + report_number(result.bic, 8),
            "residual variance RSS/(n-k) = " + report_number(result.residual_variance, 4),
            report::Inline("starts: ") << result.start_costs.size() << ", best start " << result.best_start
                                       << "; final refinement " << result.iterations << " iterations, "
                                       << (result.converged ? "converged" : "not converged") << " ("
                                       << result.stop_reason << ")"});
  report::Inline costs = "Final cost of every start:";
  for (double c : result.start_costs) costs << " " << report_number(c, 5);
  doc.paragraph(costs);

  doc.heading(2, "Modes at the estimate");
  report::Table modes{{"f [Hz]", "zeta"}, {}};
  for (const auto& m : result.modes) modes.rows.push_back({report_number(m.f_hz, 6), report_number(m.zeta, 4)});
  doc.table(std::move(modes));

  doc.heading(2, "Correlation of the estimates");
  report::Table correlation{{""}, {}};
  for (const auto& n : result.estimated) correlation.header.push_back(n);
  for (std::size_t i = 0; i < result.estimated.size(); ++i) {
    std::vector<report::Inline>& row = correlation.rows.emplace_back(1, result.estimated[i]);
    for (std::size_t k = 0; k < result.estimated.size(); ++k)
      row.push_back(report_number(result.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)), 3));
  }
  doc.table(std::move(correlation));
  report::Inline singular = "Singular values of the unit-column-scaled Jacobian of all candidates:";
  for (Eigen::Index i = 0; i < result.singular_values.size(); ++i)
    singular << " " << report_number(result.singular_values[i], 3);
  doc.paragraph(singular);
  doc.heading(2, "Data and model");

  if (std::any_of(data.begin(), data.end(), [](const DataSet& d) { return d.is_frf(); }))
    doc.paragraph(has_covariance(result)
                      ? "The shaded band around the estimate's Bode curves is +-2 standard deviations of |H| and of the "
                        "phase, from the estimate's covariance by the delta method (docs/estimation.md)."
                      : "No confidence band on the Bode curves: this fit gives no covariance of its estimate (the "
                        "method gives none, or no parameter was estimated with one).");
  std::vector<std::string> scripts;
  bool any_frf_without_band = false;
  for (std::size_t d = 0; d < data.size(); ++d) {
    doc.heading(3, report::Inline("Data set ") << d + 1 << ": " << report::code(data[d].file()));
    std::vector<report::Inline> set;
    for (const auto& [name, value] : data[d].set()) set.push_back(report::Inline("set " + name + " = ") << report::text(value.text));
    doc.list(std::move(set));
    const std::vector<std::optional<FrfBand>> bands =
        data[d].is_frf() ? estimate_bands(model, data[d], result) : std::vector<std::optional<FrfBand>>{};
    for (std::size_t c = 0; c < before.channels[d].size(); ++c) {
      const std::string label = before.channel_names[d][c];
      const std::string stem = "set" + std::to_string(d + 1) + "_" + file_stem(label);
      std::ostringstream dat;
      dat << std::setprecision(10);
      if (data[d].is_frf()) {
        const FrfData& f = std::get<FrfData>(data[d].content);
        const Eigen::VectorXcd& measured = f.channels[c].values;
        const std::optional<FrfBand>& band = bands[c];
        dat << "# f_hz |H_data| phase_data |H_prior| phase_prior |H_estimate| phase_estimate |res_prior| |res_estimate|";
        dat << (band ? " |H|-2std |H|+2std phase-2std phase+2std\n" : "\n");
        for (Eigen::Index k = 0; k < f.f_hz.size(); ++k) {
          const auto hd = measured[k], hp = before.channels[d][c][k], he = after.channels[d][c][k];
          dat << f.f_hz[k] << ' ' << std::abs(hd) << ' ' << phase_deg(hd) << ' ' << std::abs(hp) << ' ' << phase_deg(hp)
              << ' ' << std::abs(he) << ' ' << phase_deg(he) << ' ' << std::abs(hp - hd) << ' ' << std::abs(he - hd);
          if (band) {
            // A log axis has no zero: the lower edge is drawn at no less than 1 % of |H|.
            const double m = std::abs(he), sm = band->magnitude_std[k], sp = band->phase_std_deg[k];
            dat << ' ' << std::max(m - 2 * sm, 0.01 * m) << ' ' << m + 2 * sm << ' ' << phase_deg(he) - 2 * sp << ' '
                << phase_deg(he) + 2 * sp;
          }
          dat << '\n';
        }
        if (!band) any_frf_without_band = true;
        write_report_file(root / (stem + ".gp"), frf_script(stem, label, band.has_value()));
      } else {
        const TimeRecord& t = std::get<TimeRecord>(data[d].content);
        const Eigen::VectorXd& measured = t.at(label).values;
        dat << "# t y_data y_prior y_estimate res_prior res_estimate\n";
        for (Eigen::Index k = 0; k < t.samples(); ++k) {
          const double yd = measured[k], yp = before.channels[d][c][k].real(), ye = after.channels[d][c][k].real();
          dat << t.t[k] << ' ' << yd << ' ' << yp << ' ' << ye << ' ' << yp - yd << ' ' << ye - yd << '\n';
        }
        write_report_file(root / (stem + ".gp"), time_script(stem, label));
      }
      write_report_file(root / (stem + ".dat"), dat.str());
      scripts.push_back(stem);
      doc.heading(4, report::text(label));
      doc.figure(stem + ".svg", report::text(label));
      if (data[d].is_frf()) doc.figure(stem + "_residual.svg", report::Inline(report::text(label)) << " residual");
    }
  }
  if (any_frf_without_band && has_covariance(result))
    doc.paragraph("Some FRF channels have no band: the model's FRF or its Jacobian could not be evaluated at their lines.");
  estimation::residual_test_section(doc, root, result, scripts);
  estimation::validation_section(doc, root, model, validation, result, scripts);
  report::write_report(root.string(), std::move(doc), scripts);
}

}  // namespace mbgen
