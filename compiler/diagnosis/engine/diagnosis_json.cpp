#include "diagnosis/engine/diagnosis_json.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace mbgen::diagnosis {

namespace {

using nlohmann::ordered_json;

// JSON has no inf/NaN: such numbers are written as null.
ordered_json number(double x) { return std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr); }

ordered_json fit_summary(const FitResult& fit, double validation) {
  return {{"nrmse", number(fit.nrmse)}, {"bic", number(fit.bic)}, {"validation_nrmse", number(validation)}};
}

ordered_json parameter(const ParameterEstimate& p) {
  return {{"value", number(p.value)}, {"std", number(p.std)}, {"identifiable", p.identifiable}};
}

ordered_json discrepancies(const ResidualSummary& r) {
  ordered_json out = ordered_json::array();
  for (const Discrepancy& d : r.discrepancies)
    out.push_back({{"kind", d.kind}, {"channel", d.channel}, {"f_hz", number(d.f_hz)}, {"text", d.text},
                   {"data_set", d.data_set}, {"f_lo_hz", number(d.f_lo)}, {"f_hi_hz", number(d.f_hi)},
                   {"size_db", number(d.size_db)}, {"significance", number(d.significance)}});
  return out;
}

// How each channel's noise level was obtained, and how many of its lines were judged.
ordered_json noise_levels(const std::vector<ChannelResidual>& channels) {
  ordered_json out = ordered_json::array();
  for (const ChannelResidual& c : channels)
    out.push_back({{"channel", c.channel}, {"data_set", c.data_set}, {"source", c.noise},
                   {"lines_judged", c.f_hz.size()}, {"lines_not_judged", c.lines_not_judged}});
  return out;
}

}  // namespace

std::string diagnosis_json(const DiagnosisResult& result, const std::string& extended_model_path) {
  ordered_json j;
  j["schema"] = "mbgen-diagnosis/1";
  j["model"] = result.model_file;
  j["data"] = result.data;
  ordered_json nominal_params = ordered_json::object();
  for (const ParameterEstimate& p : result.nominal.fit.parameters) nominal_params[p.name] = parameter(p);
  j["nominal"] = {{"parameters", nominal_params},
                  {"fit", fit_summary(result.nominal.fit, result.nominal.validation_nrmse)},
                  {"mean_normalized_residual", number(result.nominal.residual.mean_z)},
                  {"noise", noise_levels(result.nominal.channels)}};
  j["discrepancies"] = discrepancies(result.nominal.residual);
  ordered_json candidates = ordered_json::array();
  for (const CandidateOutcome& c : result.candidates) {
    ordered_json fresh = ordered_json::object();
    for (const NewParameter& np : c.new_parameters)
      for (const ParameterEstimate& p : c.fit.parameters)
        if (p.name == np.name) fresh[p.name] = parameter(p);
    ordered_json entry = {{"id", c.id},
                          {"new_parameters", fresh},
                          {"fit", fit_summary(c.fit, c.validation_nrmse)},
                          {"delta_bic", number(c.delta_bic)},
                          {"description", c.description},
                          {"round", c.round},
                          {"plausible", c.plausible},
                          {"doubts", c.doubts},
                          {"qualifies", c.qualifies}};
    if (!c.variant.empty()) {
      entry["variant"] = c.variant;
      entry["variants_tried"] = c.variants_tried;
      entry["equivalent_variants"] = c.equivalent_variants;
    }
    if (!c.error.empty()) {
      entry["fit"] = nullptr;
      entry["delta_bic"] = nullptr;
      entry["error"] = c.error;
    }
    candidates.push_back(entry);
  }
  j["candidates"] = candidates;
  j["selected"] = result.selected;
  j["verdict"] = result.verdict;
  if (result.verdict == "extended") {
    j["extended_model"] = extended_model_path;
    j["extended"] = {{"fit", fit_summary(result.final.fit, result.final.validation_nrmse)},
                     {"mean_normalized_residual", number(result.final.residual.mean_z)},
                     {"remaining_discrepancies", discrepancies(result.final.residual)}};
  }
  return j.dump(2) + "\n";
}

}  // namespace mbgen::diagnosis
