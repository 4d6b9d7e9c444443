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
  // A parameter at a bound, or one the data do not determine, has no std (fit.hpp), as in mbgen-fit/1; the bound
  // it sits on is named.
  ordered_json out = {{"value", number(p.value)},
                      {"std", p.identifiable ? number(p.std) : ordered_json(nullptr)},
                      {"identifiable", p.identifiable}};
  if (!p.at_bound.empty()) {
    out["at_bound"] = p.at_bound;
    out["pull_chi2"] = number(p.pull_chi2);
  }
  return out;
}

ordered_json discrepancies(const ResidualSummary& r) {
  ordered_json out = ordered_json::array();
  for (const Discrepancy& d : r.discrepancies) {
    out.push_back({{"kind", d.kind}, {"channel", d.channel}, {"f_hz", number(d.f_hz)}, {"text", d.text},
                   {"data_set", d.data_set}, {"f_lo_hz", number(d.f_lo)}, {"f_hi_hz", number(d.f_hi)},
                   {"size_db", number(d.size_db)}, {"significance", number(d.significance)}});
    if (!d.parameter.empty()) out.back()["parameter"] = d.parameter;
  }
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
  j["seed"] = result.seed;
  if (!result.start_method.empty()) j["start_method"] = result.start_method;
  if (!result.warnings.empty()) j["warnings"] = result.warnings;
  ordered_json nominal_params = ordered_json::object();
  for (const ParameterEstimate& p : result.nominal.fit.parameters) nominal_params[p.name] = parameter(p);
  j["nominal"] = {{"parameters", nominal_params},
                  {"fit", fit_summary(result.nominal.fit, result.nominal.validation_nrmse)},
                  {"fit_converged", result.nominal.fit.converged},
                  {"fit_stop_reason", result.nominal.fit.stop_reason},
                  {"mean_normalized_residual", number(result.nominal.residual.mean_z)},
                  {"finding_threshold", number(result.nominal.residual.threshold)},
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
    // A freed parameter (free_parameter:P) is no new one, but its estimate is what the candidate is about.
    if (!c.freed_parameters.empty()) {
      ordered_json freed = ordered_json::object();
      for (const std::string& name : c.freed_parameters)
        for (const ParameterEstimate& p : c.fit.parameters)
          if (p.name == name) freed[p.name] = parameter(p);
      entry["freed_parameters"] = freed;
    }
    if (!c.held_parameters.empty()) entry["held_parameters"] = c.held_parameters;
    entry["screen_delta_bic"] = number(c.screen_delta_bic);
    if (c.screen_records_delta_bic != 0) entry["screen_records_delta_bic"] = number(c.screen_records_delta_bic);
    entry["fully_fitted"] = c.fully_fitted;
    if (!c.fully_fitted) entry["validation_nrmse"] = nullptr;
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
  j["selected_variants"] = result.selected_variants;
  if (!result.superseded.empty()) {
    ordered_json superseded = ordered_json::array();
    for (const DiagnosisResult::Superseded& x : result.superseded) {
      ordered_json entry = {{"id", x.id}};
      if (!x.variant.empty()) entry["variant"] = x.variant;
      entry["round"] = x.round;
      entry["bic_rise"] = number(x.bic_rise);
      superseded.push_back(entry);
    }
    j["superseded"] = superseded;
  }
  j["verdict"] = result.verdict;
  if (result.verdict == "extended") {
    j["extended_model"] = extended_model_path;
    j["extended"] = {{"fit", fit_summary(result.final.fit, result.final.validation_nrmse)},
                     {"mean_normalized_residual", number(result.final.residual.mean_z)},
                     {"remaining_discrepancies", discrepancies(result.final.residual)}};
    // Which of the nominal model's findings each selected extension explains (indices into "discrepancies").
    ordered_json explains = ordered_json::array();
    for (std::size_t i = 0; i < result.selected.size(); ++i)
      explains.push_back({{"id", result.selected[i]},
                          {"discrepancies", i < result.explains.size() ? result.explains[i] : std::vector<std::size_t>{}},
                          {"description", i < result.described.size() ? result.described[i] : std::string()}});
    j["extended"]["explains"] = explains;
  }
  // Invalid UTF-8 (a file name in another encoding) cannot be JSON text: such bytes become U+FFFD.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace mbgen::diagnosis
