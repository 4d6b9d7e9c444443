// The report and the terminal table of `mbgen modal --output-only`, laid out as the FRF path's (modal_report.cpp).
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/modal_identification/output_only_report.hpp"
#include "mbgen/report/report_document.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "text/string_format.hpp"
#include "report_text.hpp"

namespace mbgen {

namespace {

using Stability = DiagramPole::Stability;
using modal_text::fixed;
using modal_text::num;
using modal_text::stability_code;
using modal_text::write_file;

constexpr Eigen::Index kPlotLines = 4000;  // a plot's lines at most: the spectra have up to 10^5 and more

// The singular values of the output spectral matrix per line (FDD's plot, SSI-cov's background). Long spectra
// keep, of each run of lines, the one with the largest first singular value, so that no peak is lost.
std::string singular_dat(const FddResult& s) {
  std::ostringstream dat;
  dat << std::setprecision(9) << "# f_hz singular values of the output spectral matrix, descending\n";
  const Eigen::Index step = (s.f_hz.size() + kPlotLines - 1) / kPlotLines;
  for (Eigen::Index start = 0; start < s.f_hz.size(); start += step) {
    Eigen::Index k = start;
    for (Eigen::Index j = start; j < std::min(start + step, s.f_hz.size()); ++j)
      if (s.singular(j, 0) > s.singular(k, 0)) k = j;
    dat << s.f_hz[k];
    for (Eigen::Index c = 0; c < s.singular.cols(); ++c) dat << ' ' << s.singular(k, c);
    dat << '\n';
  }
  return dat.str();
}

std::string stabilization_plot(const OutputOnlyReportInput& in, bool background) {
  const StabilizationDiagram& d = method_run(in).ssi.diagram;
  std::ostringstream gp;
  gp << "set terminal svg size 1000,600 dynamic font 'sans,11'\nset output 'stabilization.svg'\n"
     << "set title 'Stabilization diagram (SSI-cov)' noenhanced\nset xlabel 'f [Hz]'\nset ylabel 'model order'\n"
     << "set xrange [0:" << d.hi_hz << "]\nset yrange [0:" << (d.orders.empty() ? 1 : d.orders.back() + 2) << "]\n"
     << "set key outside right top\nset grid xtics\nset ytics nomirror\n";
  if (background)
    gp << "set y2label 'first singular value' noenhanced\nset logscale y2\nset format y2 '%.0e'\nset y2tics\n";
  for (const OperationalMode& m : in.result.modes)
    gp << "set arrow from " << m.f_hz << ", graph 0 to " << m.f_hz << ", graph 1 nohead lc rgb '#2ca02c' dt 3\n";
  gp << "plot ";
  if (background)
    gp << "'singular.dat' using 1:2 axes x1y2 with lines lc rgb '#888888' title 'first singular value', \\\n     ";
  gp << "'stabilization.dat' using 1:($3 == 0 ? $2 : 1/0) with points pt 7 ps 0.25 lc rgb '#bbbbbb' title 'new', \\\n"
     << "     '' using 1:($3 == 1 ? $2 : 1/0) with points pt 1 ps 0.5 lc rgb '#1f77b4' title 'f', \\\n"
     << "     '' using 1:($3 == 2 ? $2 : 1/0) with points pt 2 ps 0.5 lc rgb '#9467bd' title 'f, zeta', \\\n"
     << "     '' using 1:($3 == 3 ? $2 : 1/0) with points pt 4 ps 0.5 lc rgb '#ff7f0e' title 'f, shape', \\\n"
     << "     '' using 1:($3 == 4 ? $2 : 1/0) with points pt 6 ps 0.6 lc rgb '#d62728' title 'stable'\n";
  return gp.str();
}

std::string singular_plot(const OutputOnlyReportInput& in) {
  std::ostringstream gp;
  gp << "set terminal svg size 1000,560 dynamic font 'sans,11'\nset output 'singular.svg'\n"
     << "set title 'Singular values of the output spectral matrix (FDD)' noenhanced\nset xlabel 'f [Hz]'\n"
     << "set xrange [0:" << method_run(in).fdd.f_hz[method_run(in).fdd.f_hz.size() - 1] << "]\n"
     << "set ylabel 'singular value'\nset logscale y\nset format y '%.0e'\nset grid\nset key top right\n";
  for (const OperationalMode& m : in.result.modes)
    gp << "set arrow from " << m.f_hz << ", graph 0 to " << m.f_hz << ", graph 1 nohead lc rgb '#2ca02c' dt 3\n";
  gp << "plot for [c=2:" << method_run(in).fdd.singular.cols() + 1
     << "] 'singular.dat' using 1:c with lines title sprintf('s%d', c - 1)\n";
  return gp.str();
}

std::string update_summary(const OperationalUpdate& u) {
  std::ostringstream out;
  out << "model update (" << u.model_file << "): " << u.pairs.size() << (u.pairs.size() == 1 ? " mode" : " modes")
      << " paired, chi2 " << num(u.chi2_before, 4) << " -> " << num(u.chi2_after, 4) << " over " << u.residuals
      << " residuals, " << u.iterations << " iterations" << (u.converged ? "" : " (not converged)")
      << "; standard deviations from " << u.uncertainty.blocks << " data blocks of " << num(u.uncertainty.block_s, 4)
      << " s\n";
  for (const std::string& note : u.notes) out << "note: " << note << "\n";
  out << detail::format("%-12s %-15s %14s %14s %12s\n", "parameter", "kind", "prior", "estimate", "std");
  for (const UpdatedParameter& p : u.parameters)
    out << detail::format("%-12s %-15s %14.6g %14.6g %12.3g\n", p.name.c_str(), p.kind.c_str(), p.prior, p.estimate,
                          p.std);
  out << detail::format("%4s %12s %10s %22s %22s\n", "mode", "f [Hz]", "std [Hz]", "model before (MAC)",
                        "model after (MAC)");
  for (const UpdatedPair& p : u.pairs)
    out << detail::format("%4d %12.4f %10.2g %13.4f (%.4f) %13.4f (%.4f)\n", p.mode + 1, p.f_hz, p.f_std_hz,
                          p.model_f_before, p.mac_before, p.model_f_after, p.mac_after);
  return out.str();
}

void update_section(report::Document& doc, const OperationalUpdate& u) {
  doc.heading(2, "Model update");
  doc.paragraph(report::Inline("The model ") << report::code(u.model_file)
                << " fitted to the identified modes: frequencies and shapes (after the best complex factor, as "
                   "output-only shapes are unscaled) weighted by their standard deviations, which come from "
                << u.uncertainty.blocks
                << " data blocks of " << num(u.uncertainty.block_s, 4)
                << " s (batch means); damping parameters by least squares on the damping ratios. chi2 "
                << num(u.chi2_before, 4) << " -> " << num(u.chi2_after, 4) << " over " << u.residuals
                << " residuals, " << u.iterations << " iterations" << (u.converged ? "." : " (not converged)."));
  if (!u.notes.empty()) {
    std::vector<report::Inline> notes;
    for (const std::string& n : u.notes) notes.push_back(n);
    doc.list(std::move(notes));
  }
  report::Table params{{"parameter", "kind", "prior", "estimate", "std"}, {}};
  for (const UpdatedParameter& p : u.parameters)
    params.rows.push_back({report::code(p.name), p.kind, num(p.prior, 6), num(p.estimate, 6), num(p.std, 3)});
  doc.table(std::move(params));
  report::Table pairs{{"mode", "f [Hz]", "std f [Hz]", "zeta [%]", "std zeta [%]", "model before [Hz]",
                       "error before [%]", "MAC before", "model after [Hz]", "error after [%]", "MAC after"},
                      {}};
  for (const UpdatedPair& p : u.pairs)
    pairs.rows.push_back({report::Inline() << p.mode + 1, fixed(p.f_hz, 3), num(p.f_std_hz, 2),
                          num(100 * p.zeta, 4), num(100 * p.zeta_std, 2), fixed(p.model_f_before, 3),
                          num(100 * (p.model_f_before - p.f_hz) / p.f_hz, 3), fixed(p.mac_before, 4),
                          fixed(p.model_f_after, 3), num(100 * (p.model_f_after - p.f_hz) / p.f_hz, 3),
                          fixed(p.mac_after, 4)});
  doc.table(std::move(pairs));
}

}  // namespace

std::string output_only_summary(const OutputOnlyReportInput& in) {
  const OutputOnlyIdentification& r = in.result;
  const OutputOnlyIdentification& run = method_run(in);
  const bool ssi = r.method == OutputOnlyMethod::SsiCov;
  const bool peaks = !ssi && !in.setups;  // FDD's peaks are the modes (not when setups were merged)
  std::ostringstream out;
  out << r.modes.size() << (r.modes.size() == 1 ? " mode" : " modes") << " from " << in.data.channels.size()
      << (in.data.channels.size() == 1 ? " response" : " responses") << " (output-only), "
      << output_only_method_name(r.method);
  if (ssi)
    out << ", orders 2.." << (run.ssi.diagram.orders.empty() ? 0 : run.ssi.diagram.orders.back()) << ", "
        << run.ssi.block_rows << " block rows";
  else
    out << (run.fdd.frf_inputs.empty() ? ", lag window " + num(run.fdd.window_s) + " s" : std::string(", of FRFs"));
  out << "; shapes unit-norm\n";
  for (const std::string& note : in.data.notes) out << "note: " << note << "\n";
  out << detail::format("%4s %12s %10s %7s %9s %7s\n", "mode", "f [Hz]", "zeta [%]", "MPC", "MPD [deg]",
                        ssi ? "orders" : "lines");
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const OperationalMode& mode = r.modes[m];
    out << detail::format("%4zu %12.4f %10.4f %7.4f %9.2f %7d", m + 1, mode.f_hz, 100 * mode.zeta, mode.mpc,
                          mode.mpd_deg, mode.support);
    if (peaks && !r.fdd.peaks[m].note.empty()) out << "  (EFDD: " << r.fdd.peaks[m].note << ")";
    out << "\n";
  }
  for (const RejectedPole& p : r.rejected)
    out << detail::format("dropped: a pole at %.4f Hz (%d %s): ", p.pole.f_hz, p.pole.support, ssi ? "orders" : "lines")
        << p.reason << "\n";
  if (in.update) out << update_summary(*in.update);
  return out.str();
}

void write_output_only_report(const std::string& dir, const OutputOnlyReportInput& in) {
  const ResponseData& data = in.data;
  const OutputOnlyIdentification& r = in.result;
  const OutputOnlyIdentification& run = method_run(in);
  const bool ssi = r.method == OutputOnlyMethod::SsiCov;
  const bool peaks = !ssi && !in.setups;  // FDD's peaks are the modes (not when setups were merged)
  report::Document doc;
  doc.heading(1, "Output-only modal analysis");
  report::Inline files = "Data:";
  for (const std::string& f : data.files) files << " " << report::code(f);
  doc.paragraph(files << ".");
  report::Inline channels = report::Inline("responses (") << data.channels.size() << "):";
  for (const std::string& c : data.channels) channels << " " << report::code(c);
  report::Inline references = report::Inline("references (") << data.references.size() << "):";
  for (int c : data.references) references << " " << report::code(data.channels[static_cast<std::size_t>(c)]);
  std::vector<report::Inline> settings{channels, references, "sample rate: " + num(1 / data.dt, 8) + " Hz"};
  for (const std::string& note : data.notes) settings.push_back("note: " + note);
  if (ssi) {
    const StabilizationCriteria& c = in.options.selection.criteria;
    settings.push_back("method: covariance-driven stochastic subspace identification (SSI-cov), " +
                       std::to_string(run.ssi.block_rows) + " block rows, orders 2.." +
                       std::to_string(run.ssi.diagram.orders.empty() ? 0 : run.ssi.diagram.orders.back()));
    settings.push_back("stable between orders: frequency within " + num(100 * c.frequency) + " %, damping within " +
                       num(100 * c.damping) + " %, shape MAC above " + num(1 - c.shape) +
                       "; physical poles have 0 < zeta <= " + num(c.max_zeta));
    settings.push_back("selection: automatic, clusters of stable poles at " +
                       num(100 * in.options.selection.min_orders_fraction) +
                       " % of the orders or more, contributing at least " + num(in.options.min_contribution) +
                       " of the strongest mode's peak");
  } else {
    if (run.fdd.frf_inputs.empty())
      settings.push_back("method: frequency-domain decomposition (FDD) of the spectral matrix (correlations times "
                         "exp(-|tau| / " + num(run.fdd.window_s) + " s)), damping by EFDD");
    else
      settings.push_back("method: frequency-domain decomposition (FDD) of the spectral matrix H H^H of the FRFs "
                         "(unit white forces, as the note says; no lag window), damping by EFDD");
    settings.push_back("peaks: first singular value " + num(in.options.fdd.prominence_db) +
                       " dB above its valleys; bell: MAC >= " + num(in.options.fdd.bell_mac) + ", within " +
                       num(in.options.fdd.bell_db) + " dB of the peak");
  }
  doc.list(std::move(settings));
  if (in.setups) {
    doc.heading(2, "Setups");
    doc.paragraph("Each setup identified on its own; a mode of the first setup is kept when every other has one "
                  "within the frequency criterion. f and zeta are the means over the setups (*scatter* their standard "
                  "deviations), the shape the first setup's extended by the others' scaled to it on the references. "
                  "The diagram below is the first setup's.");
    report::Table t{{"setup", "files", "responses", "modes [Hz]"}, {}};
    for (std::size_t s = 0; s < in.setups->setups.size(); ++s) {
      report::Inline files, channels, modes;
      for (const std::string& f : in.setups->setups[s].files) files << report::code(f) << " ";
      for (const std::string& c : in.setups->setups[s].channels) channels << report::code(c) << " ";
      for (const OperationalMode& m : in.setups->per_setup[s].modes) modes << fixed(m.f_hz, 2) << " ";
      t.rows.push_back({report::Inline() << s + 1, files, channels, modes});
    }
    doc.table(std::move(t));
  }

  doc.heading(2, "Modes");
  doc.paragraph(ssi ? "f and zeta are the medians of the mode's cluster of stable poles; *scatter* is their standard "
                      "deviation over the orders (not an uncertainty). Shapes are unscaled (no force was measured): "
                      "unit norm, largest component real and positive. *Contribution*: the mode's resonance peak in "
                      "the correlations relative to the strongest."
                    : "f and zeta by EFDD from the correlation function of the mode's bell (the peak's line when that "
                      "failed). Shapes from records: the residue of the mode's pole term fitted in the half spectra "
                      "over its bell (its left singular vector); from FRFs: the first singular vector at the peak. "
                      "Unit norm, largest component real and positive (unscaled).");
  report::Table modes{{"mode", "f [Hz]", "zeta [%]", "MPC", "MPD [deg]"}, {}};
  if (ssi)
    for (const char* h : {"scatter f [Hz]", "scatter zeta [%]", "orders", "contribution"}) modes.header.push_back(h);
  else if (peaks)
    for (const char* h : {"peak f [Hz]", "bell lines", "EFDD note"}) modes.header.push_back(h);
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const OperationalMode& mode = r.modes[m];
    std::vector<report::Inline> row{report::Inline() << m + 1, fixed(mode.f_hz, 3), num(100 * mode.zeta, 4),
                                    fixed(mode.mpc, 3), fixed(mode.mpd_deg, 1)};
    if (ssi) {
      row.push_back(num(mode.f_scatter_hz, 2));
      row.push_back(num(100 * mode.zeta_scatter, 2));
      row.push_back(report::Inline() << mode.support);
      row.push_back(num(mode.contribution, 3));
    } else if (peaks) {
      row.push_back(fixed(r.fdd.peaks[m].f_hz, 3));
      row.push_back(report::Inline() << mode.support);
      row.push_back(r.fdd.peaks[m].note);
    }
    modes.rows.push_back(std::move(row));
  }
  doc.table(std::move(modes));
  if (!r.rejected.empty()) {
    std::vector<report::Inline> dropped;
    for (const RejectedPole& p : r.rejected)
      dropped.push_back(report::Inline(fixed(p.pole.f_hz, 3)) << " Hz, zeta " << num(100 * p.pole.zeta, 3) << " %, "
                                                              << p.pole.support << (ssi ? " orders: " : " lines: ")
                                                              << p.reason);
    doc.paragraph("Clusters dropped:");
    doc.list(std::move(dropped));
  }

  if (in.update) update_section(doc, *in.update);

  std::vector<std::string> stems;
  const FddResult* spectrum = ssi ? in.spectrum : &run.fdd;
  if (spectrum) write_file(dir, "singular.dat", singular_dat(*spectrum));
  if (ssi) {
    std::ostringstream stab;
    stab << std::setprecision(9) << "# f_hz order stability(0 new, 1 f, 2 f+zeta, 3 f+shape, 4 stable) zeta\n";
    for (const DiagramPole& p : run.ssi.diagram.poles)
      stab << p.f_hz << ' ' << p.order << ' ' << stability_code(p.stability) << ' ' << p.zeta << '\n';
    write_file(dir, "stabilization.dat", stab.str());
    write_file(dir, "stabilization.gp", stabilization_plot(in, spectrum != nullptr));
    stems.push_back("stabilization");
    doc.heading(2, "Stabilization diagram");
    doc.paragraph("Each pole against the nearest of the order below: grey new, blue stable in frequency, purple also "
                  "in damping, orange also in shape, red circles stable in all three; dotted green lines are the "
                  "selected modes. The grey curve is the first singular value of the output spectral matrix.");
    doc.figure("stabilization.svg", "stabilization diagram");
  } else {
    write_file(dir, "singular.gp", singular_plot(in));
    stems.push_back("singular");
    doc.heading(2, "Singular values");
    doc.paragraph("The singular values of the output spectral matrix per line; dotted green lines are the modes.");
    doc.figure("singular.svg", "singular values");
  }
  if (!r.modes.empty()) {
    doc.heading(2, "Auto-MAC");
    std::vector<std::string> labels;
    for (std::size_t m = 0; m < r.modes.size(); ++m)
      labels.push_back(std::to_string(m + 1) + " (" + fixed(r.modes[m].f_hz, 1) + " Hz)");
    report::Table t{{""}, {}};
    for (const std::string& l : labels) t.header.push_back(l);
    for (Eigen::Index i = 0; i < r.auto_mac.rows(); ++i) {
      std::vector<report::Inline>& row = t.rows.emplace_back(1, labels[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < r.auto_mac.cols(); ++j) row.push_back(fixed(r.auto_mac(i, j), 2));
    }
    doc.table(std::move(t));
  }
  report::write_report(dir, std::move(doc), stems);
}

}  // namespace mbgen
