#include "diagnosis/engine/model_fits.hpp"

#include <algorithm>

#include <mbgen/residuals/channel_residuals.hpp>

#include "diagnosis/engine/candidate_judging.hpp"
#include "evaluator/symbolic_evaluator.hpp"

namespace mbgen::diagnosis {

namespace {

// `fo` estimates every parameter of role estimate but those `held` at their values (none held: FitOptions' own
// choice stands).
void estimate_all_but(const ModelInfo& info, const std::vector<std::string>& held, FitOptions& fo) {
  if (held.empty()) return;
  for (const ParameterInfo& p : info.parameters)
    if (p.role == ParameterRole::Estimate && std::find(held.begin(), held.end(), p.name) == held.end())
      fo.estimate.push_back(p.name);
}

}  // namespace

std::map<std::string, double> values_by_name(const ModelInfo& info, const Eigen::VectorXd& values) {
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < info.parameters.size(); ++i)
    out[info.parameters[i].name] = values[static_cast<Eigen::Index>(i)];
  return out;
}

std::map<std::string, double> estimated_values(const ModelInfo& info, const std::map<std::string, double>& values) {
  std::map<std::string, double> out;
  for (const auto& [name, v] : values) {
    const int i = info.parameter_index(name);
    if (i >= 0 && info.parameters[static_cast<std::size_t>(i)].role == ParameterRole::Estimate) out[name] = v;
  }
  return out;
}

ModelState renamed(const ModelState& twin, const Extension& ext, const ModelInfo& info) {
  std::map<std::string, std::string> to;
  for (std::size_t i = 0; i < info.parameters.size(); ++i) to[twin.info.parameters[i].name] = info.parameters[i].name;
  const auto rename = [&](std::string& name) {
    const auto it = to.find(name);
    if (it != to.end()) name = it->second;
  };
  ModelState s = twin;
  s.model = ext.model;
  s.text = ext.mdl_text;
  s.info = info;
  for (ParameterEstimate& p : s.fit.parameters) {
    rename(p.name);
    for (std::string& other : p.confounded_with) rename(other);
  }
  for (std::string& name : s.fit.estimated) rename(name);
  for (std::string& name : s.held) rename(name);
  s.values = values_by_name(info, s.fit.values);
  return s;
}

FitContext::FitContext(const std::vector<DataSet>& data, const DiagnoseOptions& options)
    : data_(data),
      options_(options),
      split_(split_for_validation(options.fit_data ? *options.fit_data : data)),
      has_records_(std::any_of(data.begin(), data.end(), [](const DataSet& d) { return !d.is_frf(); })),
      screen_data_(split_.fit) {}

void FitContext::screen_on_h1(std::vector<DataSet> h1, int averages) {
  screen_data_ = std::move(h1);
  screen_averages_ = averages;
  screen_on_companion_ = true;
}

FitOptions FitContext::local_fit_options(const ModelInfo& info, const std::map<std::string, double>& from) const {
  FitOptions fo = options_.fit;
  fo.values = estimated_values(info, from);
  fo.also_start_at.clear();
  fo.optimum_start_at.clear();
  fo.further_starts_at.clear();
  fo.settle_first.clear();
  fo.threads = 1;
  fo.progress = nullptr;
  return fo;
}

std::unique_ptr<Model> FitContext::derive_model(const ir::ModelIr& model) const {
  symbolic::DeriveOptions derive;
  derive.set = options_.set;
  return evaluator::make_evaluator(model, derive);
}

ModelState FitContext::assess(const ir::ModelIr& model, const std::string& text,
                              const std::map<std::string, double>& start, int starts) const {
  return assess(*derive_model(model), model, text, start, starts, Workers{options_.fit.threads, nullptr, nullptr});
}

ModelState FitContext::assess(const Model& evaluator, const ir::ModelIr& model, const std::string& text,
                              const std::map<std::string, double>& start, int starts, const Workers& workers,
                              const std::map<std::string, double>& also_start_at, const std::vector<std::string>& held,
                              const std::vector<std::map<std::string, double>>& further_starts_at,
                              const std::map<std::string, double>& optimum_start_at,
                              const std::vector<std::string>& settle_first) const {
  FitOptions fo = options_.fit;
  fo.also_start_at = also_start_at;
  fo.optimum_start_at = optimum_start_at;
  fo.further_starts_at = further_starts_at;
  fo.settle_first = settle_first;
  estimate_all_but(evaluator.info(), held, fo);
  const ModelInfo& info = evaluator.info();
  for (const auto& [name, v] : estimated_values(info, start)) fo.values[name] = v;
  fo.starts = starts + static_cast<int>(further_starts_at.size()) + static_cast<int>(!optimum_start_at.empty());
  fo.threads = workers.threads;
  fo.cores = workers.cores;
  fo.memo = workers.memo;
  fo.stall_gain = workers.stall_gain;
  // Two fits may run at once (candidates on worker threads): their progress reaches the caller one at a time.
  if (options_.fit.progress)
    fo.progress = [this](const FitProgress& p) {
      std::lock_guard<std::mutex> lock(fit_progress_mutex_);
      options_.fit.progress(p);
    };
  ModelState s;
  s.model = model;
  s.text = text;
  s.info = info;
  s.held = held;
  s.fit = fit(evaluator, split_.fit, fo);
  s.values = values_by_name(info, s.fit.values);
  s.validation_nrmse = validation_nrmse(evaluator, split_, s.fit.values, fo.frf_weighting);
  s.channels = channel_residuals(evaluator, data_, s.fit.values, fo.frf_weighting, {&split_.fit, &s.fit.estimated});
  s.residual = analyse_residuals(s.channels, options_.residual);
  for (Discrepancy& d : bound_findings(s.fit, info)) s.residual.discrepancies.push_back(std::move(d));
  return s;
}

bool FitContext::leads_lower_on_companion(const Model& evaluator, const std::vector<std::string>& held,
                                          const std::map<std::string, double>& start,
                                          const std::map<std::string, double>& own) const {
  if (!screen_on_companion_) return true;
  const std::optional<double> from = bic_on_companion(evaluator, held, start);
  const std::optional<double> from_own = bic_on_companion(evaluator, held, own);
  if (!from || !from_own) return true;  // not judged on the H1: refit on the records
  return *from < *from_own + options_.min_delta_bic;
}

std::optional<double> FitContext::bic_on_companion(const Model& evaluator, const std::vector<std::string>& held,
                                                   const std::map<std::string, double>& start) const {
  if (!screen_on_companion_) return std::nullopt;
  FitOptions fo = local_fit_options(evaluator.info(), start);
  estimate_all_but(evaluator.info(), held, fo);
  fo.starts = 1;
  fo.frf_weighting.averages = std::max(fo.frf_weighting.averages, screen_averages_);
  try {
    return fit(evaluator, screen_data_, fo).bic;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

void FitContext::say(const std::string& line) const {
  std::lock_guard<std::mutex> lock(fit_progress_mutex_);
  if (options_.progress) options_.progress(line);
}

}  // namespace mbgen::diagnosis
