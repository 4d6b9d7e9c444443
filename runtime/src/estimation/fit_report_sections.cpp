// The fit report's residual-test and validation sections (fit_report_sections.hpp).
#include "fit_report_sections.hpp"

#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/report_files.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <complex>
#include <iomanip>
#include <sstream>

namespace mbgen::estimation {

namespace {

double phase_deg(std::complex<double> h) { return numerics::degrees(std::arg(h)); }

// One block of a correlation plot's data: lag, value, band (gnuplot `index` selects it).
std::string correlation_block(const CorrelationTest& t) {
  std::ostringstream out;
  out << std::setprecision(10) << "# lag value band\n";
  for (std::size_t i = 0; i < t.lags.size(); ++i) out << t.lags[i] << ' ' << t.values[i] << ' ' << t.band << '\n';
  return out.str();
}

// Stems (impulses) of every block with its band drawn dashed on both sides; block 0 the whiteness, then one per input.
std::string correlation_script(const std::string& stem, const std::string& title,
                               const std::vector<std::string>& panel_titles, int max_lag) {
  std::ostringstream gp;
  const std::size_t panels = panel_titles.size();
  gp << "set terminal svg size 900," << 250 + 230 * panels << " dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set multiplot layout " << panels << ",1 title " << gnuplot_string(title) << " noenhanced\n"
     << "set grid\nset key top right\nset xlabel 'lag [samples]'\n";
  for (std::size_t p = 0; p < panels; ++p) {
    gp << "set xrange [" << (p == 0 ? -1 : -max_lag - 1) << ":" << max_lag + 1 << "]\n"
       << "set title " << gnuplot_string(panel_titles[p]) << " noenhanced\n"
       << "plot '" << stem << ".dat' index " << p
       << " using 1:2 with impulses lw 2 lc rgb '#1f77b4' notitle, \\\n"
       << "     '' index " << p << " using 1:2 with points pt 7 ps 0.4 lc rgb '#1f77b4' notitle, \\\n"
       << "     '' index " << p << " using 1:3 with lines dt 2 lc rgb '#d62728' title '99 % band', \\\n"
       << "     '' index " << p << " using 1:(-$3) with lines dt 2 lc rgb '#d62728' notitle\n";
  }
  gp << "unset multiplot\n";
  return gp.str();
}

report::Inline fraction(const CorrelationTest& t) {
  return report::Inline(std::to_string(t.outside) + " of " + std::to_string(t.judged) + " (" +
                        report_number(100 * t.fraction_outside(), 3) + " %)");
}

std::string validation_frf_script(const std::string& stem, const std::string& title) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,700 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set multiplot layout 2,1 title " << gnuplot_string(title) << " noenhanced\n"
     << "set logscale y\nset format y '%.0e'\nset grid\nset ylabel '|H|'\nset key top right\n"
     << "plot '" << stem << ".dat' using 1:2 with points pt 7 ps 0.3 lc rgb '#555555' title 'validation data', \\\n"
     << "     '' using 1:4 with lines lc rgb '#d62728' title 'model, estimate'\n"
     << "unset logscale y\nset format y '%g'\nset ylabel 'phase [deg]'\nset xlabel 'f [Hz]'\nset yrange [-180:180]\nset ytics 90\n"
     << "plot '" << stem << ".dat' using 1:3 with points pt 7 ps 0.3 lc rgb '#555555' title 'validation data', \\\n"
     << "     '' using 1:5 with lines lc rgb '#d62728' title 'model, estimate'\n"
     << "unset multiplot\n";
  return gp.str();
}

std::string validation_time_script(const std::string& stem, const std::string& title) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,400 dynamic font 'sans,11'\n"
     << "set output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title) << " noenhanced\nset grid\nset key top right\n"
     << "set ylabel 'output'\nset xlabel 't [s]'\n"
     << "plot '" << stem << ".dat' using 1:2 with lines lc rgb '#555555' title 'validation data', \\\n"
     << "     '' using 1:3 with lines lc rgb '#d62728' title 'model, estimate'\n";
  return gp.str();
}

}  // namespace

void residual_test_section(report::Document& doc, const std::filesystem::path& root, const FitResult& result,
                           std::vector<std::string>& scripts) {
  if (result.residual_tests.empty()) return;
  doc.heading(2, "Residual tests");
  doc.paragraph(report::Inline("The residual e = y - y_model of each record's output at the estimate (the model "
                               "simulated from the record's inputs): its normalised autocorrelation for lags 1 to L "
                               "should stay within +-2.58/sqrt(N) if e is white, and its cross-correlation with each "
                               "input for lags -L to L within Ljung's band +-2.58 sqrt(P/N), P = sum of rho_e(k) "
                               "rho_u(k), if e is independent of the input (99 % bands). A verdict fails when more "
                               "lags lie outside than noise alone leaves there in 99 % of cases, or when one lag lies "
                               "beyond the simultaneous 99 % band of all the lags (Bonferroni). L = ")
                << result.residual_test_lags << ". An output-error fit models no noise: coloured measurement "
                   "noise makes the residual not white while the model is right; a residual correlated with the "
                   "input is a model error.");
  report::Table table{{"data set", "output", "test", "lags outside the band", "band", "verdict"}, {}};
  for (std::size_t c = 0; c < result.residual_tests.size(); ++c) {
    const ChannelResidualTest& t = result.residual_tests[c];
    table.rows.push_back({report::code(t.data_set), report::text(t.output), "whiteness", fraction(t.whiteness),
                          report_number(t.whiteness.band, 3), t.whiteness.passed() ? "white" : "**not white**"});
    for (const auto& [input, x] : t.inputs)
      table.rows.push_back({report::code(t.data_set), report::text(t.output),
                            report::Inline("cross-correlation with ") << report::text(input), fraction(x),
                            report_number(x.band, 3),
                            x.passed() ? "independent of the input" : "**correlated with the input**"});
  }
  doc.table(std::move(table));
  for (std::size_t c = 0; c < result.residual_tests.size(); ++c) {
    const ChannelResidualTest& t = result.residual_tests[c];
    const std::string stem = "resid" + std::to_string(c + 1) + "_" + file_stem(t.output);
    std::string dat = correlation_block(t.whiteness);
    std::vector<std::string> panels{"autocorrelation of the residual of " + t.output};
    for (const auto& [input, x] : t.inputs) {
      dat += "\n\n" + correlation_block(x);
      panels.push_back("cross-correlation of the residual of " + t.output + " with " + input);
    }
    write_report_file(root / (stem + ".dat"), dat);
    write_report_file(root / (stem + ".gp"), correlation_script(stem, t.data_set + ": " + t.output, panels, t.whiteness.lags.back()));
    scripts.push_back(stem);
    doc.figure(stem + ".svg", report::Inline("residual tests of ") << report::text(t.output));
  }
}

void validation_section(report::Document& doc, const std::filesystem::path& root, const Model& model,
                        const std::vector<DataSet>& validation, const FitResult& result,
                        std::vector<std::string>& scripts) {
  if (validation.empty()) return;
  doc.heading(2, "Validation on other data");
  doc.paragraph("The model at the estimate on data it was not fitted to, scored as MATLAB's compare: fit % = "
                "100 (1 - ||y - y_model|| / ||y - mean(y)||) for a record's output, 100 (1 - ||H - H_model|| / ||H||) "
                "for an FRF (complex values over the lines, no mean removed). 100 is a perfect match.");
  report::Table table{{"file", "channel", "fit %"}, {}};
  for (const ValidationScore& v : result.validation)
    for (const ChannelValidation& c : v.channels)
      table.rows.push_back({report::code(v.file), report::text(c.channel), report_number(c.fit_percent, 4)});
  doc.table(std::move(table));
  for (std::size_t d = 0; d < validation.size(); ++d) {
    doc.heading(3, report::Inline("Validation data ") << d + 1 << ": " << report::code(validation[d].file()));
    Prediction at_estimate;
    try {
      at_estimate = predict(model, {validation[d]}, result.values);
    } catch (const std::exception& e) {
      doc.paragraph(report::Inline("Not drawn: ") << report::text(e.what()) << ".");
      continue;
    }
    for (std::size_t c = 0; c < at_estimate.channels[0].size(); ++c) {
      const std::string label = at_estimate.channel_names[0][c];
      const std::string stem = "validate" + std::to_string(d + 1) + "_" + file_stem(label);
      std::ostringstream dat;
      dat << std::setprecision(10);
      const Eigen::VectorXcd& model_values = at_estimate.channels[0][c];
      if (validation[d].is_frf()) {
        const FrfData& f = std::get<FrfData>(validation[d].content);
        dat << "# f_hz |H_data| phase_data |H_estimate| phase_estimate\n";
        for (Eigen::Index k = 0; k < f.f_hz.size(); ++k) {
          const auto hd = f.channels[c].values[k], he = model_values[k];
          dat << f.f_hz[k] << ' ' << std::abs(hd) << ' ' << phase_deg(hd) << ' ' << std::abs(he) << ' '
              << phase_deg(he) << '\n';
        }
        write_report_file(root / (stem + ".gp"), validation_frf_script(stem, validation[d].file() + ": " + label));
      } else {
        const TimeRecord& t = std::get<TimeRecord>(validation[d].content);
        const Eigen::VectorXd& measured = t.at(label).values;
        dat << "# t y_data y_estimate\n";
        for (Eigen::Index k = 0; k < t.samples(); ++k)
          dat << t.t[k] << ' ' << measured[k] << ' ' << model_values[k].real() << '\n';
        write_report_file(root / (stem + ".gp"), validation_time_script(stem, validation[d].file() + ": " + label));
      }
      write_report_file(root / (stem + ".dat"), dat.str());
      scripts.push_back(stem);
      doc.figure(stem + ".svg", report::Inline("validation: ") << report::text(label));
    }
  }
}

}  // namespace mbgen::estimation
