// The report directory of `mbgen modal`: report.md and report.html with the mode table and SVG plots drawn by
// gnuplot from .dat files and .gp scripts (the scripts stay, so plots can be redrawn where gnuplot was missing).
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/modal_identification/modal_report.hpp"
#include "mbgen/report/report_document.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "text/string_format.hpp"
#include "modal_shape_figures.hpp"
#include "report_text.hpp"
#include "numerics/constants.hpp"

namespace mbgen {

namespace {

using Stability = DiagramPole::Stability;
using modal_text::fixed;
using modal_text::num;
using modal_text::stability_code;
using modal_text::write_file;

double phase_deg(std::complex<double> h) { return numerics::degrees(std::arg(h)); }

std::string quantity_text(const ModalReportInput& in) {
  std::string text = frf_quantity_name(in.data.quantity);
  if (in.data.quantity == FrfQuantity::Unknown)
    return text + " (the residual terms are fitted to the data as given: pass --quantity to say which)";
  return in.quantity_source.empty() ? text : text + " (" + in.quantity_source + ")";
}

std::string stabilization_plot(const ModalReportInput& in, const std::string& ylabel) {
  std::ostringstream gp;
  gp << "set terminal svg size 1000,600 dynamic font 'sans,11'\nset output 'stabilization.svg'\n"
     << "set title 'Stabilization diagram' noenhanced\nset xlabel 'f [Hz]'\nset ylabel 'model order'\n"
     << "set y2label " << gnuplot_string(ylabel) << " noenhanced\nset logscale y2\nset format y2 '%.0e'\nset y2tics\n"
     << "set ytics nomirror\nset xrange [" << in.data.f_hz[0] << ":" << in.data.f_hz[in.data.f_hz.size() - 1] << "]\n"
     << "set yrange [0:" << (in.result.diagram.orders.empty() ? 1 : in.result.diagram.orders.back() + 1) << "]\n"
     << "set key outside right top\nset grid xtics\n";
  for (const IdentifiedMode& m : in.result.modes)
    gp << "set arrow from " << m.f_hz << ", graph 0 to " << m.f_hz << ", graph 1 nohead lc rgb '#2ca02c' dt 3\n";
  gp << "plot 'sum.dat' using 1:2 axes x1y2 with lines lc rgb '#888888' title 'sum of |H|', \\\n"
     << "     'stabilization.dat' using 1:($3 == 0 ? $2 : 1/0) with points pt 7 ps 0.25 lc rgb '#bbbbbb' title 'new', "
        "\\\n"
     << "     '' using 1:($3 == 1 ? $2 : 1/0) with points pt 1 ps 0.5 lc rgb '#1f77b4' title 'f', \\\n"
     << "     '' using 1:($3 == 2 ? $2 : 1/0) with points pt 2 ps 0.5 lc rgb '#9467bd' title 'f, zeta', \\\n"
     << "     '' using 1:($3 == 3 ? $2 : 1/0) with points pt 4 ps 0.5 lc rgb '#ff7f0e' title 'f, shape', \\\n"
     << "     '' using 1:($3 == 4 ? $2 : 1/0) with points pt 6 ps 0.6 lc rgb '#d62728' title 'stable'\n";
  return gp.str();
}

std::string mac_plot(const std::string& stem, const std::string& title, const std::string& xlabel,
                     const std::string& ylabel) {
  std::ostringstream gp;
  gp << "set terminal svg size 560,480 dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title) << " noenhanced\nset xlabel " << gnuplot_string(xlabel) << "\nset ylabel "
     << gnuplot_string(ylabel) << "\nset cbrange [0:1]\nset palette defined (0 'white', 1 '#1f3b73')\n"
     << "set size ratio -1\nset tics out\nset autoscale fix\n"
     << "plot '" << stem << ".dat' using ($1 + 1):($2 + 1):3 matrix with image notitle, \\\n"
     << "     '' using ($1 + 1):($2 + 1):(sprintf('%.2f', $3)) matrix with labels font ',8' notitle\n";
  return gp.str();
}

std::string matrix_dat(const Eigen::MatrixXd& m) {
  std::ostringstream dat;
  dat << std::setprecision(6);
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) dat << (j ? " " : "") << m(i, j);
    dat << '\n';
  }
  return dat.str();
}

std::string frf_plot(const std::string& stem, const std::string& title) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,640 dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
     << "set multiplot layout 2,1 title " << gnuplot_string(title) << " noenhanced\n"
     << "set logscale y\nset format y '%.0e'\nset grid\nset ylabel '|H|'\nset key top right\n"
     << "plot '" << stem << ".dat' using 1:2 with points pt 7 ps 0.3 lc rgb '#555555' title 'measured', \\\n"
     << "     '' using 1:4 with lines lc rgb '#d62728' title 'synthesized'\n"
     << "unset logscale y\nset format y '%g'\nset ylabel 'phase [deg]'\nset xlabel 'f [Hz]'\nset yrange [-180:180]\n"
     << "set ytics 90\n"
     << "plot '" << stem << ".dat' using 1:3 with points pt 7 ps 0.3 lc rgb '#555555' title 'measured', \\\n"
     << "     '' using 1:5 with lines lc rgb '#d62728' title 'synthesized'\nunset multiplot\n";
  return gp.str();
}

report::Table mac_table(const Eigen::MatrixXd& mac, const std::vector<std::string>& rows,
                        const std::vector<std::string>& cols) {
  report::Table t{{""}, {}};
  for (const std::string& c : cols) t.header.push_back(c);
  for (Eigen::Index i = 0; i < mac.rows(); ++i) {
    std::vector<report::Inline>& row = t.rows.emplace_back(1, rows[static_cast<std::size_t>(i)]);
    for (Eigen::Index j = 0; j < mac.cols(); ++j) row.push_back(fixed(mac(i, j), 2));
  }
  return t;
}

}  // namespace

std::string modal_summary(const ModalReportInput& in) {
  const ModalIdentification& r = in.result;
  std::ostringstream out;
  out << r.modes.size() << (r.modes.size() == 1 ? " mode" : " modes") << " from " << in.data.channels.size()
      << (in.data.channels.size() == 1 ? " channel, " : " channels, ") << num(in.data.f_hz[0], 6) << ".."
      << num(in.data.f_hz[in.data.f_hz.size() - 1], 6) << " Hz (" << frf_quantity_name(in.data.quantity) << "), "
      << r.method << ", orders 1.." << (r.diagram.orders.empty() ? 0 : r.diagram.orders.back()) << "\n";
  out << detail::format("%4s %12s %9s %10s %9s %7s %9s %7s%s\n", "mode", "f [Hz]", "std", "zeta [%]", "std", "MPC",
                        "MPD [deg]", "orders", in.model ? "   model mode (f [Hz], MAC)" : "");
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const IdentifiedMode& mode = r.modes[m];
    out << detail::format("%4zu %12.4f %9.2g %10.4f %9.2g %7.4f %9.2f %7d", m + 1, mode.f_hz, mode.f_std_hz,
                          100 * mode.zeta, 100 * mode.zeta_std, mode.mpc, mode.mpd_deg, mode.support);
    if (in.model && in.model->pairing.model_mode[m] >= 0) {
      const int k = in.model->pairing.model_mode[m];
      out << detail::format("   %d (%.4f, %.3f)%s", k, in.model->modes.f_hz[static_cast<std::size_t>(k)],
                            in.model->pairing.best_mac[m], in.model->pairing.shared[m] ? " shared" : "");
    }
    out << (mode.user_selected ? "  (selected by frequency)" : "") << (mode.refined ? "" : "  (not refined)") << "\n";
  }
  for (const RejectedPole& p : r.rejected) {
    out << detail::format("dropped: a pole at %.4f Hz (%d orders): ", p.pole.f_hz, p.pole.support) << p.reason << "\n";
  }
  return out.str();
}

void write_modal_report(const std::string& dir, const ModalReportInput& in) {
  const ModalData& data = in.data;
  const ModalIdentification& r = in.result;
  const StabilizationDiagram& diagram = r.diagram;
  const Eigen::Index lines = data.f_hz.size();
  report::Document doc;
  doc.heading(1, "Modal analysis");
  report::Inline files = "Data:";
  for (const std::string& f : data.files) files << " " << report::code(f);
  doc.paragraph(files << ".");
  report::Inline channels = report::Inline("channels (") << data.channels.size() << "):";
  for (const ModalData::Channel& c : data.channels) channels << " " << report::code(c.name);
  doc.list({channels,
            "band: " + num(data.f_hz[0], 8) + " to " + num(data.f_hz[lines - 1], 8) + " Hz, " +
                std::to_string(lines) + " lines",
            "FRF quantity: " + quantity_text(in),
            report::Inline("poles: ")
                << (diagram.references > 1 ? "poly-reference least-squares complex-frequency method (PolyMAX), "
                                           : "least-squares complex-frequency method (LSCF, common denominator), ")
                << diagram.references << " reference" << (diagram.references > 1 ? "s" : "")
                << (diagram.transposed ? " (the outputs; rows are the inputs)" : "")
                << ", z-domain basis with dt = 1/(2 * " << num(diagram.hi_hz, 8) << " Hz), orders 1.."
                << (diagram.orders.empty() ? 0 : diagram.orders.back()),
            "stable between orders: frequency within " + num(100 * in.options.selection.criteria.frequency) +
                " %, damping within " + num(100 * in.options.selection.criteria.damping) + " %, shape MAC above " +
                num(1 - in.options.selection.criteria.shape) +
                "; physical poles have 0 < zeta <= " + num(in.options.selection.criteria.max_zeta),
            "selection: " + (in.options.select_hz.empty()
                                 ? "automatic, clusters of stable poles found at " +
                                       num(100 * in.options.selection.min_orders_fraction) + " % of the orders or more"
                                 : std::string("the poles nearest the frequencies given")),
            std::string("residues: LSFD") + (in.options.lsfd.lower_residual ? ", lower residual" : "") +
                (in.options.lsfd.upper_residual ? ", upper residual" : "")});

  doc.heading(2, "Modes");
  doc.paragraph("f and zeta after the refinement (their standard deviations from its Jacobian and misfit; before it, "
                "the LSCF cluster's median). Residues (the `shape` in the JSON) are those of the measured FRF. MPC is "
                "1 for a real (normal) mode shape; MPD is the mean phase deviation from a straight line. *Orders* "
                "counts the model orders whose pole joined the mode's cluster.");
  report::Table modes{{"mode", "f [Hz]", "std f [Hz]", "zeta [%]", "std zeta [%]", "LSCF f [Hz]", "LSCF zeta [%]",
                       "MPC", "MPD [deg]", "orders"},
                      {}};
  if (in.model)
    for (const char* h : {"model mode", "model f [Hz]", "model zeta [%]", "MAC"}) modes.header.push_back(h);
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const IdentifiedMode& mode = r.modes[m];
    std::vector<report::Inline> row{
        report::Inline() << m + 1, fixed(mode.f_hz, 3), mode.refined ? num(mode.f_std_hz, 2) : "not refined",
        num(100 * mode.zeta, 4), mode.refined ? num(100 * mode.zeta_std, 2) : "", fixed(mode.lscf_f_hz, 3),
        num(100 * mode.lscf_zeta, 4), fixed(mode.mpc, 3), fixed(mode.mpd_deg, 1),
        report::Inline() << mode.support << (mode.user_selected ? " (selected)" : "")};
    if (in.model) {
      const int k = in.model->pairing.model_mode[m];
      if (k >= 0) {
        row.push_back(report::Inline() << k);
        row.push_back(fixed(in.model->modes.f_hz[static_cast<std::size_t>(k)], 3));
        row.push_back(num(100 * in.model->modes.zeta[static_cast<std::size_t>(k)], 4));
        row.push_back(fixed(in.model->pairing.best_mac[m], 3) + (in.model->pairing.shared[m] ? " (shared)" : ""));
      } else {
        for (const char* cell : {"—", "", "", ""}) row.push_back(cell);
      }
    }
    modes.rows.push_back(std::move(row));
  }
  doc.table(std::move(modes));
  if (in.options.refine)
    doc.paragraph("Refinement (variable projection on the LSFD misfit, channels weighted by 1/RMS): weighted misfit " +
                  num(r.refinement.initial_cost) + " at the LSCF poles, " + num(r.refinement.cost) + " after.");
  for (std::size_t m = 0; m < r.refinement.notes.size(); ++m)
    if (!r.refinement.notes[m].empty()) doc.list({"held at its LSCF value: " + r.refinement.notes[m]});
  if (!r.rejected.empty()) {
    doc.paragraph("Candidates dropped because the refinement could not hold them (the misfit has no minimum near "
                  "them: no resonance of the data):");
    std::vector<report::Inline> dropped;
    for (const RejectedPole& p : r.rejected)
      dropped.push_back(report::Inline(fixed(p.pole.f_hz, 3)) << " Hz, zeta " << num(100 * p.pole.zeta, 3) << " %, "
                                                              << p.pole.support << " orders: " << p.reason);
    doc.list(std::move(dropped));
  }
  if (r.modes.empty())
    doc.paragraph("No physical pole was found: see the stabilization diagram, and select poles by frequency.");

  // Stabilization diagram over the sum of the FRFs' magnitudes.
  std::ostringstream stab, sum;
  stab << std::setprecision(9) << "# f_hz order stability(0 new, 1 f, 2 f+zeta, 3 f+shape, 4 stable) zeta\n";
  for (const DiagramPole& p : diagram.poles)
    stab << p.f_hz << ' ' << p.order << ' ' << stability_code(p.stability) << ' ' << p.zeta << '\n';
  sum << std::setprecision(9) << "# f_hz sum_c |H_c|\n";
  for (Eigen::Index k = 0; k < lines; ++k) sum << data.f_hz[k] << ' ' << data.H.row(k).cwiseAbs().sum() << '\n';
  write_file(dir, "stabilization.dat", stab.str());
  write_file(dir, "sum.dat", sum.str());
  write_file(dir, "stabilization.gp",
             stabilization_plot(in, "sum of |H| (" + std::string(frf_quantity_name(data.quantity)) + ")"));
  std::vector<std::string> stems{"stabilization"};
  doc.heading(2, "Stabilization diagram");
  doc.paragraph("Each pole against the nearest of the order below: grey new, blue stable in frequency, purple also in "
                "damping, orange also in shape, red circles stable in all three; dotted green lines are the selected "
                "modes. The grey curve is the sum of the FRFs' magnitudes.");
  doc.figure("stabilization.svg", "stabilization diagram");

  std::vector<std::string> mode_labels;
  for (std::size_t m = 0; m < r.modes.size(); ++m)
    mode_labels.push_back(std::to_string(m + 1) + " (" + fixed(r.modes[m].f_hz, 1) + " Hz)");
  if (!r.modes.empty()) {
    doc.heading(2, "Auto-MAC");
    doc.paragraph("MAC between the identified modes' residue vectors (off-diagonal values near 1 mean the channels "
                  "cannot tell two modes apart).");
    doc.table(mac_table(r.auto_mac, mode_labels, mode_labels));
    write_file(dir, "auto_mac.dat", matrix_dat(r.auto_mac));
    write_file(dir, "auto_mac.gp", mac_plot("auto_mac", "auto-MAC", "mode", "mode"));
    stems.push_back("auto_mac");
    doc.figure("auto_mac.svg", "auto-MAC");
  }
  if (in.model && std::find(in.model->pairing.shared.begin(), in.model->pairing.shared.end(), true) !=
                      in.model->pairing.shared.end())
    doc.paragraph("*(shared)*: another identified mode has the same best-matching model mode. The channels cannot "
                  "tell their shapes apart (few sensors, or all on one line), or the model lacks a mode the structure "
                  "has; compare the frequencies.");
  if (in.model && !r.modes.empty()) {
    std::vector<std::string> model_labels;
    for (std::size_t k = 0; k < in.model->modes.f_hz.size(); ++k)
      model_labels.push_back(std::to_string(k) + " (" + fixed(in.model->modes.f_hz[k], 1) + " Hz)");
    doc.heading(2, "MAC against the model");
    doc.paragraph(report::Inline("Model ") << report::code(in.model->model_file)
                                           << " at its parameter values; its residues at the measured channels (rows: "
                                              "identified modes, columns: model modes as `mbgen inspect` lists them, "
                                              "from 0).");
    doc.table(mac_table(in.model->pairing.mac, mode_labels, model_labels));
    write_file(dir, "model_mac.dat", matrix_dat(in.model->pairing.mac));
    write_file(dir, "model_mac.gp",
               mac_plot("model_mac", "MAC: identified vs model", "model mode + 1", "identified mode"));
    stems.push_back("model_mac");
    doc.figure("model_mac.svg", "MAC against the model");
  }

  add_identified_mode_figures(doc, dir, in);

  doc.heading(2, "Synthesized and measured FRFs");
  doc.paragraph("The modal model (the selected poles, the residues and the residual terms) against the data. Error: "
                "||H - H_synthesized|| / ||H|| over the band.");
  report::Table errors{{"channel", "error", "lower residual", "upper residual"}, {}};
  for (std::size_t c = 0; c < data.channels.size(); ++c) {
    const Eigen::Index ci = static_cast<Eigen::Index>(c);
    errors.rows.push_back({report::code(data.channels[c].name), num(r.fit.channel_error[ci], 3),
                           num(r.fit.lower[ci], 4), num(r.fit.upper[ci], 4)});
  }
  doc.table(std::move(errors));
  for (std::size_t c = 0; c < data.channels.size(); ++c) {
    const Eigen::Index ci = static_cast<Eigen::Index>(c);
    const std::string stem = "frf_" + std::to_string(c + 1);
    std::ostringstream dat;
    dat << std::setprecision(9) << "# f_hz |H| phase |H_synthesized| phase_synthesized\n";
    for (Eigen::Index k = 0; k < lines; ++k) {
      const std::complex<double> h = data.H(k, ci), s = r.fit.synthesized(k, ci);
      dat << data.f_hz[k] << ' ' << std::abs(h) << ' ' << phase_deg(h) << ' ' << std::abs(s) << ' ' << phase_deg(s)
          << '\n';
    }
    write_file(dir, stem + ".dat", dat.str());
    write_file(dir, stem + ".gp", frf_plot(stem, data.channels[c].name));
    stems.push_back(stem);
    doc.heading(3, report::code(data.channels[c].name));
    doc.figure(stem + ".svg", report::text(data.channels[c].name));
  }
  report::write_report(dir, std::move(doc), stems);
}

}  // namespace mbgen
