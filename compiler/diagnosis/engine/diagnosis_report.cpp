#include "diagnosis/engine/diagnosis_report.hpp"

#include <mbgen/report/gnuplot.hpp>
#include <mbgen/report/report_document.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace mbgen::diagnosis {

namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": error: cannot write the report");
}

std::string num(double x, int digits = 4) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string frf_script(const std::string& stem, const std::string& title, bool extended) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,420 dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title) << " noenhanced\n"
     << "set logscale y\nset grid\nset xlabel 'f [Hz]'\nset ylabel '|H|'\n"
     << "plot '" << stem << ".dat' using 1:2 with points pt 7 ps 0.3 lc rgb '#555555' title 'data', \\\n"
     << "     '' using 1:3 with lines lc rgb '#1f77b4' dt 2 title 'nominal model'";
  if (extended) gp << ", \\\n     '' using 1:4 with lines lc rgb '#d62728' title 'extended model'";
  gp << "\n";
  return gp.str();
}

std::string residual_script(const std::string& stem, const std::string& title, bool extended) {
  std::ostringstream gp;
  gp << "set terminal svg size 900,320 dynamic font 'sans,11'\nset output '" << stem << ".svg'\n"
     << "set title " << gnuplot_string(title + " (1 = noise level)") << " noenhanced\n"
     << "set logscale y\nset grid\nset xlabel 'f [Hz]'\n"
     << "set ylabel '|residual|^2 / noise^2'\n"
     << "plot '" << stem << ".dat' using 1:2 with lines lc rgb '#1f77b4' title 'nominal'";
  if (extended) gp << ", \\\n     '' using 1:3 with lines lc rgb '#d62728' title 'extended'";
  gp << ", 1 with lines lc rgb '#2ca02c' dt 3 title 'noise'\n";
  return gp.str();
}

report::Table parameter_table(const FitResult& fit) {
  report::Table t{{"parameter", "prior", "estimate", "std", "identifiable"}, {}};
  for (const ParameterEstimate& p : fit.parameters)
    t.rows.push_back({"`" + p.name + "`", num(p.prior, 6), num(p.value, 6),
                      p.at_bound.empty() ? num(p.std, 3) : std::string("—"),
                      p.identifiable        ? "yes"
                      : p.at_bound.empty() ? "**no** (kept at prior)"
                                           : "**no**: at its " + p.at_bound + " bound"});
  return t;
}

// The channel (index into the nominal channels) that finding d is on; -1 for none (a parameter at a bound).
int channel_of(const DiagnosisResult& r, const Discrepancy& d) {
  for (std::size_t c = 0; c < r.nominal.channels.size(); ++c)
    if (r.nominal.channels[c].channel == d.channel && r.nominal.channels[c].data_set == d.data_set)
      return static_cast<int>(c);
  return -1;
}

// What a reader needs on the first screen, under the verdict: the strongest findings (the list is strongest first)
// and the overlay of data and models on the channel of the strongest, whose figure the plots section also shows.
void first_screen(report::Document& doc, const DiagnosisResult& r) {
  const std::vector<Discrepancy>& all = r.nominal.residual.discrepancies;
  if (all.empty()) return;
  constexpr std::size_t kShown = 3;
  std::vector<report::Inline> strongest;
  for (std::size_t k = 0; k < all.size() && k < kShown; ++k)
    strongest.push_back(report::text(reader_text(r, all[k].text)));
  doc.paragraph(all.size() > kShown ? "The strongest findings (of " + std::to_string(all.size()) + ", all below):"
                                    : std::string("The findings:"));
  doc.list(std::move(strongest));
  for (const Discrepancy& d : all) {
    const int c = channel_of(r, d);
    if (c < 0) continue;
    const ChannelResidual& channel = r.nominal.channels[static_cast<std::size_t>(c)];
    doc.figure("frf_" + std::to_string(c) + ".svg",
               report::text(channel.channel + " (" + fs::path(channel.data_set).filename().string() +
                            "), where the strongest finding is"));
    break;
  }
}

}  // namespace

std::string reader_text(const DiagnosisResult& r, const std::string& finding_text) {
  std::string text = finding_text;
  for (const std::string& path : r.data) {
    const std::string full = " (" + path + ")";
    const std::string brief = r.data.size() == 1 ? "" : " (" + fs::path(path).filename().string() + ")";
    for (std::size_t at = text.find(full); at != std::string::npos; at = text.find(full, at + brief.size()))
      text.replace(at, full.size(), brief);
  }
  return text;
}

void write_diagnosis_report(const std::string& dir, const DiagnosisResult& r) {
  const fs::path root(dir);
  fs::create_directories(root);
  const bool extended = r.verdict == "extended";
  report::Document doc;
  doc.heading(1, report::Inline("Diagnosis of ") << report::code(r.model_file));
  for (const std::string& w : r.warnings) doc.paragraph(report::Inline("**Warning:** ") << report::text(w) << ".");
  report::Inline data = "Data: ";
  for (std::size_t i = 0; i < r.data.size(); ++i) data << (i ? ", " : "") << report::code(r.data[i]);
  doc.paragraph(data);
  doc.heading(2, "Verdict: " + r.verdict);
  if (extended) {
    report::Inline selected = "Selected: ";
    for (std::size_t i = 0; i < r.selected.size(); ++i) selected << (i ? ", " : "") << "`" << r.selected[i] << "`";
    doc.paragraph(selected << ". Mean normalized residual " << num(r.nominal.residual.mean_z) << " -> "
                           << num(r.final.residual.mean_z) << " (1 is the noise level); validation error "
                           << num(r.nominal.validation_nrmse) << " -> " << num(r.final.validation_nrmse) << ".");
    // What each selected extension says, and which of the nominal model's findings it explains.
    std::vector<report::Inline> said;
    for (std::size_t i = 0; i < r.selected.size(); ++i) {
      const CandidateOutcome* o = selected_outcome(r, r.selected[i]);
      if (!o) continue;
      const std::string& description = i < r.described.size() ? r.described[i] : o->description;
      report::Inline& line =
          said.emplace_back(report::Inline(report::code(r.selected[i])) << ": " << report::text(description));
      // The findings it explains, the strongest few (the list is strongest first); all are listed below.
      if (i < r.explains.size() && !r.explains[i].empty()) {
        constexpr std::size_t kNamed = 2;
        const std::vector<std::size_t>& cleared = r.explains[i];
        line << ". It explains " << cleared.size() << (cleared.size() == 1 ? " finding" : " findings")
             << " of the nominal model" << (cleared.size() > kNamed ? ", the strongest: " : ": ");
        for (std::size_t k = 0; k < cleared.size() && k < kNamed; ++k)
          line << (k ? "; " : "") << report::text(reader_text(r, r.nominal.residual.discrepancies[cleared[k]].text));
      } else if (i < r.explains.size()) {
        std::string alone = kExplainsNoFindingAlone;
        alone[0] = 'I';  // a sentence of its own here, a clause under the extension on standard output
        line << ". " << report::text(alone);
      }
    }
    doc.list(std::move(said));
    for (const DiagnosisResult::Superseded& x : r.superseded)
      doc.paragraph(report::Inline(report::code(x.id)) << (x.variant.empty() ? "" : " (" + x.variant + ")")
                                                       << ", taken in round " << x.round
                                                       << ", was dropped again: the extension taken after it does its "
                                                          "work (without it the BIC changes by "
                                                       << num(x.bic_rise) << ").");
  } else if (r.verdict == "unexplained") {
    doc.paragraph("The model misses the data beyond the noise, and no candidate extension explains it (see the "
                  "findings and the ranking below).");
  } else {
    doc.paragraph("Nothing beyond the noise remains: the nominal model explains the data.");
  }

  if (!r.nominal.fit.converged)
    doc.paragraph("**The nominal model's fit did not converge** (" + r.nominal.fit.stop_reason +
                  "): some findings may be the fit's, not the model's.");
  first_screen(doc, r);
  doc.heading(2, "What the nominal model gets wrong");
  if (r.nominal.residual.discrepancies.empty()) doc.paragraph("No finding above the noise level.");
  std::vector<report::Inline> findings, noise;
  const std::vector<Discrepancy>& nominal_findings = r.nominal.residual.discrepancies;
  for (std::size_t k = 0; k < nominal_findings.size(); ++k) {
    const Discrepancy& d = nominal_findings[k];
    report::Inline& line =
        findings.emplace_back(report::Inline(report::text(reader_text(r, d.text))) << " (`" << d.kind << "`)");
    if (!extended) continue;
    for (std::size_t i = 0; i < r.explains.size() && i < r.selected.size(); ++i)
      if (std::find(r.explains[i].begin(), r.explains[i].end(), k) != r.explains[i].end())
        line << ": explained by " << report::code(r.selected[i]);
  }
  doc.list(std::move(findings));
  doc.paragraph("The noise level each channel is judged against (1 in the normalized residual):");
  for (const ChannelResidual& c : r.nominal.channels) {
    report::Inline& line = noise.emplace_back(c.channel + " (`" + fs::path(c.data_set).filename().string() + "`): " +
                                              c.noise);
    if (c.lines_not_judged > 0)
      line << "; " << c.lines_not_judged << " of " << (c.lines_not_judged + static_cast<long>(c.f_hz.size()))
           << " lines not judged (the data there are noise)";
  }
  doc.list(std::move(noise));
  doc.heading(2, "Candidates");
  report::Table candidates{
      {"round", "id", "ΔBIC", "validation nrmse", "plausible", "qualifies", "what it adds"},
      {{"", "nominal", "0", num(r.nominal.validation_nrmse), "", "", ""}}};
  for (const CandidateOutcome& c : r.candidates) {
    const report::Inline round = report::Inline() << c.round, id = "`" + c.id + "`";
    if (!c.error.empty())
      candidates.rows.push_back({round, id, "failed", "", "", "", report::text(c.error)});
    else if (!c.fully_fitted)
      candidates.rows.push_back(
          {round, id, "screened out (" + num(c.screen_delta_bic, 5) + " in screening)", "", "", "no", c.description});
    else
      candidates.rows.push_back(
          {round, id, num(c.delta_bic, 5), num(c.validation_nrmse),
           c.plausible ? "yes" : "no: " + (c.doubts.empty() ? std::string() : c.doubts.front()),
           c.qualifies ? "**yes**" : "no", c.description});
  }
  doc.table(std::move(candidates));
  doc.paragraph("Every candidate is first fitted cheaply (local fits near the current estimate, and from the priors "
                "where it has no point at which it is the current model); the best by that screening are fitted "
                "fully. A candidate qualifies when its BIC is lower by more than 10, its validation error is lower, "
                "and its new parameters are plausible; the best one is selected if it also explains the "
                "discrepancy.");

  doc.heading(2, "Parameters of the nominal model");
  doc.table(parameter_table(r.nominal.fit));
  if (extended) {
    doc.heading(2, "Parameters of the extended model");
    doc.table(parameter_table(r.final.fit));
  }

  doc.heading(2, "Plots");
  std::vector<std::string> stems;
  for (std::size_t c = 0; c < r.nominal.channels.size(); ++c) {
    const ChannelResidual& nominal = r.nominal.channels[c];
    const ChannelResidual* final = extended && c < r.final.channels.size() ? &r.final.channels[c] : nullptr;
    const std::string label = nominal.channel + " (" + fs::path(nominal.data_set).filename().string() + ")";
    const std::string frf_stem = "frf_" + std::to_string(c), res_stem = "residual_" + std::to_string(c);
    std::ostringstream frf_dat, res_dat;
    frf_dat << std::setprecision(9);
    res_dat << std::setprecision(9);
    for (std::size_t k = 0; k < nominal.f_hz.size(); ++k) {
      const Eigen::Index i = static_cast<Eigen::Index>(k);
      const double s2 = nominal.sigma[i] * nominal.sigma[i];
      frf_dat << nominal.f_hz[k] << ' ' << std::abs(nominal.measured[i]) << ' ' << std::abs(nominal.model[i]);
      res_dat << nominal.f_hz[k] << ' ' << std::norm(nominal.measured[i] - nominal.model[i]) / s2;
      if (final) {
        frf_dat << ' ' << std::abs(final->model[i]);
        res_dat << ' ' << std::norm(final->measured[i] - final->model[i]) / s2;
      }
      frf_dat << '\n';
      res_dat << '\n';
    }
    write_file(root / (frf_stem + ".dat"), frf_dat.str());
    write_file(root / (res_stem + ".dat"), res_dat.str());
    write_file(root / (frf_stem + ".gp"), frf_script(frf_stem, label, final != nullptr));
    write_file(root / (res_stem + ".gp"), residual_script(res_stem, "normalized residual, " + label, final != nullptr));
    stems.push_back(frf_stem);
    stems.push_back(res_stem);
    doc.heading(3, report::text(label));
    doc.figure(frf_stem + ".svg", report::text(label));
    doc.figure(res_stem + ".svg", "residual");
  }
  report::write_report(root.string(), std::move(doc), stems);
}

}  // namespace mbgen::diagnosis
