#include "diagnosis/engine/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <set>

#include <mbgen/residuals/chain_scores.hpp>
#include <mbgen/residuals/channel_residuals.hpp>
#include <mbgen/residuals/data_split.hpp>
#include <mbgen/dynamics/frf.hpp>
#include <mbgen/methods/modal_start.hpp>
#include <mbgen/dynamics/parallel.hpp>
#include <mbgen/residuals/same_response.hpp>
#include <mbgen/estimation/spectral_companion.hpp>

#include "diagnosis/engine/driving_points.hpp"
#include "diagnosis/engine/judging.hpp"
#include "diagnosis/engine/new_body_modes.hpp"
#include "diagnosis/engine/text_format.hpp"
#include "diagnosis/engine/thresholds.hpp"
#include "diagnosis/text_patch.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"

namespace mbgen::diagnosis {

namespace {

// The measurement chain's operator (docs/diagnosis.md, "The measurement chain"): its candidates are fitted only where
// a statistic at the current fit or against the priors supports them (chain_scores.hpp).
const char* const kChainOperator = "measurement_chain";
// Chain candidates fitted per round: the best by their statistic.
constexpr std::size_t kChainFits = 3;
// How close the slope of log |data / model| against log f must come to a whole number k for data of another form
// ((i w)^k off the model) to be taken as evidence: a quarter of a decade per decade.
constexpr double kFormSlopeTolerance = 0.25;

// Parameters the data sets set to different values (e.g. a spin speed), counting "not set" as a value of its own:
// what a model must follow across data sets.
std::set<std::string> varying_parameters(const std::vector<DataSet>& data) {
  std::set<std::string> names;
  for (const DataSet& d : data)
    for (const auto& entry : d.set()) names.insert(entry.first);
  std::set<std::string> out;
  for (const std::string& name : names) {
    std::set<std::string> values;
    for (const DataSet& d : data) {
      const auto it = d.set().find(name);
      values.insert(it == d.set().end() ? std::string("<default>") : it->second.text);
    }
    if (values.size() > 1) out.insert(name);
  }
  return out;
}

// The names of the parameters the selected extensions added.
std::set<std::string> added_parameters(const DiagnosisResult& r) {
  std::set<std::string> names;
  for (const CandidateOutcome& c : r.candidates)
    if (std::find(r.selected.begin(), r.selected.end(), c.id) != r.selected.end())
      for (const NewParameter& p : c.new_parameters) names.insert(p.name);
  return names;
}

// The extended model's text with the added parameters' start values replaced by their estimates, so the written
// model is the fitted one: their numbers replaced in place through TextPatch.
std::string with_estimates(const std::string& text, const std::string& file, const std::map<std::string, double>& values,
                           const std::set<std::string>& names) {
  const ir::ModelIr parsed = frontend::parse_string(text, file);
  TextPatch patch(text, file);
  for (const ir::Parameter& p : parsed.parameters) {
    const auto it = values.find(p.name);
    if (!names.count(p.name) || it == values.end() || p.derived) continue;
    char number[64];
    std::snprintf(number, sizeof number, "%.6g", it->second);
    patch.replace_number(p.loc, number);
  }
  return patch.text();
}

// `text` with parameter `name`'s declaration changed from `estimate` to `known`, saying why in its comment.
std::string with_role_known(const std::string& text, const std::string& file, const std::string& name) {
  const ir::ModelIr parsed = frontend::parse_string(text, file);
  TextPatch patch(text, file);
  for (const ir::Parameter& p : parsed.parameters)
    if (p.name == name && p.role == ir::Role::Estimate)
      patch.change_role(p.loc, "estimate", "known", "held at this value: the data do not determine it");
  return patch.text();
}

// The values of `values` that model `info` estimates: start values for its fit. Its known and fixed parameters keep
// their own (another model's estimate of a parameter this one holds fixed must not leak into it).
std::map<std::string, double> estimated_values(const ModelInfo& info, const std::map<std::string, double>& values) {
  std::map<std::string, double> out;
  for (const auto& [name, v] : values) {
    const int i = info.parameter_index(name);
    if (i >= 0 && info.parameters[static_cast<std::size_t>(i)].role == ParameterRole::Estimate) out[name] = v;
  }
  return out;
}

// The parameters a taken model's fit held (ModelState::held) become `known` in its model and text, so that later
// fits keep them and the written model says so.
void declare_held_known(ModelState& s) {
  for (const std::string& name : s.held) {
    for (ir::Parameter& p : s.model.parameters)
      if (p.name == name) p.role = ir::Role::Known;
    s.text = with_role_known(s.text, s.model.file, name);
  }
  s.held.clear();
}

// Whether the fit pressed an estimate against one of its bounds: it stands at the bound (within a thousandth of
// it, or, for a bound at zero, below a thousandth of its prior: the bounded fit approaches zero by factors, never
// reaching it) and the data pull it further out (more than 10 in chi-square: ParameterEstimate::pull_chi2). A
// parameter the data barely see may drift to a bound with nothing pulling it: that is no misfit. "upper" or
// "lower", or empty.
std::string pressed_bound(const ParameterEstimate& p, const ParameterInfo& info) {
  if (!p.estimated || !p.identifiable || p.pull_chi2 <= thresholds::kBoundPullChi2) return {};
  const auto at = [&](double bound) {
    if (!std::isfinite(bound)) return false;
    if (bound == 0) return std::abs(p.value) <= thresholds::kAtBoundRelative * std::abs(p.prior);
    return std::abs(p.value - bound) <= thresholds::kAtBoundRelative * std::max(std::abs(bound), std::abs(p.value));
  };
  if (p.toward < 0 && at(info.lower)) return "lower";
  if (p.toward > 0 && at(info.upper)) return "upper";
  return {};
}

// Findings of a fit that needs values its model does not allow: each estimate pressed against a bound.
std::vector<Discrepancy> bound_findings(const FitResult& fit, const ModelInfo& info) {
  std::vector<Discrepancy> out;
  for (const ParameterEstimate& p : fit.parameters) {
    const int i = info.parameter_index(p.name);
    if (i < 0) continue;
    const ParameterInfo& pi = info.parameters[static_cast<std::size_t>(i)];
    const std::string side = pressed_bound(p, pi);
    if (side.empty()) continue;
    Discrepancy d;
    d.kind = "parameter_at_bound";
    d.parameter = p.name;
    char text[256];
    std::snprintf(text, sizeof text,
                  "the fit pressed %s against its %s bound (%.4g%s%s): the model fits the data only with values it "
                  "does not allow",
                  p.name.c_str(), side.c_str(), side == "lower" ? pi.lower : pi.upper, pi.unit.empty() ? "" : " ",
                  pi.unit.c_str());
    d.text = text;
    out.push_back(d);
  }
  return out;
}

std::map<std::string, double> values_by_name(const ModelInfo& info, const Eigen::VectorXd& values) {
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < info.parameters.size(); ++i) out[info.parameters[i].name] = values[static_cast<Eigen::Index>(i)];
  return out;
}

class Diagnoser {
 public:
  Diagnoser(const std::vector<DataSet>& data, const DiagnoseOptions& options)
      : data_(data),
        options_(options),
        split_(split_for_validation(options.fit_data ? *options.fit_data : data)),
        has_records_(std::any_of(data.begin(), data.end(), [](const DataSet& d) { return !d.is_frf(); })) {
    screen_data_ = split_.fit;
  }

  // Where a fit runs: on `threads` workers of its own, or (`cores` set) on its caller's thread and the free cores of
  // a budget it shares with the fits beside it (a round's candidates: the core that finished the short ones joins
  // the starts of the long one).
  // `memo`: the local fits of this model already run (FitOptions::memo), shared by a candidate's screening and full
  // fits, which start from the same points.
  struct Workers {
    int threads = 1;
    std::shared_ptr<ThreadBudget> cores;
    std::shared_ptr<estimation::LocalFitMemo> memo;
  };

  // Fits `model` (parameters started at `start` where named) and judges it.
  ModelState assess(const ir::ModelIr& model, const std::string& text, const std::map<std::string, double>& start,
                    int starts) const {
    return assess(*derive_model(model), model, text, start, starts, Workers{options_.fit.threads, nullptr, nullptr});
  }

  // The same with `model` already derived (`evaluator`), the fit on `workers`. Uses no GiNaC: safe on a worker
  // thread.
  // `held`: parameters with role estimate that this fit keeps at their values (the others are estimated).
  // `further_starts_at`, `optimum_start_at`: starts of the fit's search in addition to its `starts` (FitOptions).
  ModelState assess(const mbgen::Model& evaluator, const ir::ModelIr& model, const std::string& text,
                    const std::map<std::string, double>& start, int starts, const Workers& workers,
                    const std::map<std::string, double>& also_start_at = {},
                    const std::vector<std::string>& held = {},
                    const std::vector<std::map<std::string, double>>& further_starts_at = {},
                    const std::map<std::string, double>& optimum_start_at = {}) const {
    FitOptions fo = options_.fit;
    fo.also_start_at = also_start_at;
    fo.optimum_start_at = optimum_start_at;
    fo.further_starts_at = further_starts_at;
    if (!held.empty())
      for (const ParameterInfo& p : evaluator.info().parameters)
        if (p.role == ParameterRole::Estimate && std::find(held.begin(), held.end(), p.name) == held.end())
          fo.estimate.push_back(p.name);
    const ModelInfo& info = evaluator.info();
    for (const auto& [name, v] : estimated_values(info, start)) fo.values[name] = v;
    fo.starts = starts + static_cast<int>(further_starts_at.size()) + static_cast<int>(!optimum_start_at.empty());
    fo.threads = workers.threads;
    fo.cores = workers.cores;
    fo.memo = workers.memo;
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

  // Derivation and tape compilation use GiNaC, which is not thread-safe: only ever on the calling thread.
  std::unique_ptr<mbgen::Model> derive_model(const ir::ModelIr& model) const {
    symbolic::DeriveOptions derive;
    derive.set = options_.set;
    return evaluator::make_evaluator(model, derive);
  }

  // The loop of the method (docs/diagnosis.md): fit and judge the nominal model, extend it greedily one candidate
  // per round while a candidate explains what is wrong, then keep the extension only if it explains enough.
  DiagnosisResult run(const ir::ModelIr& model, const std::string& text) {
    DiagnosisResult result;
    result.model_file = model.file;
    result.seed = options_.fit.seed;
    for (const DataSet& d : data_) result.data.push_back(d.file());
    reversed_ = reversed_driving_points(model, data_);
    result.nominal = assess_nominal(model, text);
    ModelState current = result.nominal;
    // The stopping rule: a model that shows no finding is adequate, and no candidate is fitted. The findings'
    // threshold holds the family-wise false-alarm rate over every window of lines judged at 0.05
    // (residual_analysis.hpp, finding_threshold), so a right model is extended, or called unexplained, at most that
    // often (docs/diagnosis.md, "The stopping rule").
    for (int round = 1; round <= options_.max_extensions; ++round) {
      if (current.residual.discrepancies.empty()) {
        if (round == 1) say("nominal model: no finding beyond the noise; nothing to extend");
        break;
      }
      // A further round pursues what the nominal model gets wrong and the extensions taken have not explained, or,
      // while the extended model would not be kept (full_explanation), what it still shows: an effect the nominal
      // fit masked (a loose mount that shows only once an added mass is in). Once every nominal finding is explained
      // and the model would be kept, what the extended model alone shows is the form of its extensions (a base on
      // feet where the real base's feet stand elsewhere), which another extension would only tune: on such data a
      // joining spring from the housing to the floor "explained" the on-feet base's own misfit (delta BIC -1229).
      if (round > 1 && pending_findings(result, current).empty() &&
          full_explanation(result, current, options_).holds) {
        say(format("round %.0f: every finding of the nominal model is explained; the %.0f the extended model still "
                   "shows are the form of its extensions, not a further effect",
                   static_cast<double>(round), static_cast<double>(current.residual.discrepancies.size())));
        break;
      }
      if (!extend_once(round, result, current)) break;
    }
    keep_only_full_explanations(result, current);
    if (!result.selected.empty())
      current.text = with_estimates(current.text, current.model.file, current.values, added_parameters(result));
    result.final = current;
    result.verdict = verdict_of(result);
    say("verdict: " + result.verdict);
    return result;
  }

 private:
  // Fits and judges the nominal model; its findings steer the candidates (sensor outputs), and with records the
  // screening runs on the records' H1 estimates, where a fit needs no simulation (records too short for them are
  // screened on themselves).
  ModelState assess_nominal(const ir::ModelIr& model, const std::string& text) {
    say("nominal model: fitting " + std::to_string(model.parameters.size()) + " parameters");
    // The caller's chosen starts (monitor: the baseline's levels), and the start from the data's modes before them.
    const std::unique_ptr<mbgen::Model> evaluator = derive_model(model);
    FitOptions fo = options_.fit;
    if (options_.start_from_modes) {
      const ModalStart from_modes = start_from_modes(*evaluator, split_.fit, options_.fit);
      say("nominal model: start from the data's modes: " + from_modes.summary);
      start_first_at(from_modes.values, fo);
    }
    ModelState nominal = assess(*evaluator, model, text, {}, fo.starts, Workers{options_.fit.threads, nullptr, nullptr},
                                fo.also_start_at, {}, fo.further_starts_at);
    sensor_outputs_ = outputs_missed_alone(nominal.channels);
    if (has_records_) {
      if (const auto companion = estimation::spectral_companion(nominal.info, split_.fit)) {
        screen_data_ = companion->data;
        screen_averages_ = companion->averages;
        screen_on_companion_ = true;
      }
    }
    say(format("nominal model: nrmse %.4g, validation %.4g, mean normalized residual %.3g", nominal.fit.nrmse,
               nominal.validation_nrmse, nominal.residual.mean_z));
    for (const Discrepancy& d : nominal.residual.discrepancies) say("  finding: " + d.text);
    return nominal;
  }

  // One round of the greedy forward selection: every candidate on the current model, scored; the best qualifying one
  // is taken if it explains the discrepancy. Another round follows while the extended model still shows a finding:
  // two independent effects (a sensor's calibration and a loose mount) are named one per round, and a candidate that
  // did not qualify against the nominal model may against the extended one (the loose mount, once the calibration is
  // right). False when the search ends.
  bool extend_once(int round, DiagnosisResult& result, ModelState& current) {
    prior_peaks_ = prior_peaks(current.model);
    const ExtensionContext ctx = context(current);
    std::string hints;
    for (double f : ctx.peak_hz) hints += format(" %.1f", f);
    if (!hints.empty()) say("round " + std::to_string(round) + ": peaks to place new modes at (Hz):" + hints);
    std::vector<Extension> extensions = enumerate_extensions(current.model, current.text, ctx);
    // The measurement chain's candidates come first in the list; only those the data support are fitted.
    const auto structural = std::stable_partition(extensions.begin(), extensions.end(), [](const Extension& e) {
      return e.operator_name == kChainOperator;
    });
    std::vector<Extension> chain(std::make_move_iterator(extensions.begin()), std::make_move_iterator(structural));
    chain = chain_candidates_worth_fitting(std::move(chain), current);
    extensions.erase(extensions.begin(), structural);
    extensions.insert(extensions.begin(), std::make_move_iterator(chain.begin()), std::make_move_iterator(chain.end()));
    if (extensions.empty()) return false;
    std::vector<CandidateOutcome> outcomes;
    std::vector<ModelState> states;
    score_all(extensions, current, round, outcomes, states);
    keep_best_variants(outcomes, states);
    result.candidates.insert(result.candidates.end(), outcomes.begin(), outcomes.end());
    const std::size_t first_of_round = result.candidates.size() - outcomes.size();
    const int best = best_after_refits(result, current, outcomes, states, first_of_round);
    if (best < 0) return false;
    const Judgement agreed = predicts_as_well(outcomes, best);
    if (!agreed.holds) {
      say(agreed.why);
      return false;
    }
    ModelState& chosen = states[static_cast<std::size_t>(best)];
    const Judgement explained = explains(current, chosen, round < options_.max_extensions);
    if (!explained.why.empty()) say(explained.why);
    if (!explained.holds) return false;
    result.selected.push_back(outcomes[static_cast<std::size_t>(best)].id);
    result.explains.push_back(findings_cleared(result, current, chosen));
    for (const std::string& id : equivalents(outcomes, best))
      say("  " + id + " fits exactly as well: the same extension in another place");
    say("selected " + result.selected.back());
    declare_held_known(chosen);
    current = std::move(chosen);
    return !current.residual.discrepancies.empty();
  }

  // With records: whether a model, fitted on the records' H1 estimates from `start` (another model's estimates),
  // ends lower there in BIC than fitted from its own estimate `own`. A better optimum shows on the H1 as well, where
  // a fit costs milliseconds; only then is the model refitted on the records, where a model that misses an effect
  // crawls (a spindle without its base: 835 record iterations, 27 s, for a BIC 2 lower). True without a companion:
  // the refit itself is the test. `held`: estimated parameters kept at their values, as in assess().
  bool leads_lower_on_companion(const mbgen::Model& evaluator, const std::vector<std::string>& held,
                                const std::map<std::string, double>& start,
                                const std::map<std::string, double>& own) const {
    if (!screen_on_companion_) return true;
    const ModelInfo& info = evaluator.info();
    const auto local_fit = [&](const std::map<std::string, double>& from) {
      FitOptions fo = options_.fit;
      fo.values = estimated_values(info, from);
      if (!held.empty())
        for (const ParameterInfo& p : info.parameters)
          if (p.role == ParameterRole::Estimate && std::find(held.begin(), held.end(), p.name) == held.end())
            fo.estimate.push_back(p.name);
      fo.also_start_at.clear();
      fo.optimum_start_at.clear();
      fo.further_starts_at.clear();
      fo.starts = 1;
      fo.threads = 1;
      fo.progress = nullptr;
      fo.frf_weighting.averages = std::max(fo.frf_weighting.averages, screen_averages_);
      return fit(evaluator, screen_data_, fo);
    };
    try {
      return local_fit(start).bic < local_fit(own).bic + options_.min_delta_bic;
    } catch (const std::exception&) {
      return true;  // not judged on the H1: refit on the records
    }
  }

  // Time derivatives of displacement an output kind reads ("displacement" 0, "velocity" 1, "acceleration" 2).
  static int derivative_order(const std::string& kind) {
    return kind == "velocity" ? 1 : kind == "acceleration" ? 2 : 0;
  }

  // The chain candidates whose statistic at the current fit says the data would support them (chain_scores.hpp): a
  // factor on an output's (or an input's) channels whose score statistic exceeds ln(n), the BIC price of the factor
  // with n residuals, in the variants of the factor's sign only (calibration g > 0; polarity g < 0 and reversed
  // g = -1); two outputs whose exchanged data lower chi-square by more than ln(n); an output whose data fit better as
  // another form of its quantity (form_gain) by more than ln(n). The kChainFits best by statistic are fitted; a
  // driving point that gives out power (driving_points.hpp) puts its force's and its sensor's negative variants
  // first. The statistics take milliseconds: where the data's chain is right, no chain candidate is fitted.

  std::vector<Extension> chain_candidates_worth_fitting(std::vector<Extension> extensions,
                                                        const ModelState& current) const {
    const double price = std::log(std::max(2.0, static_cast<double>(current.fit.residual_count)));
    // Evidence in tiers: 0 the data alone (a driving point's phase), 1 the current fit, 2 only the priors.
    struct Worth {
      int tier;
      double statistic;
      std::size_t index;
    };
    std::vector<Worth> worth;
    for (std::size_t k = 0; k < extensions.size(); ++k) {
      const Extension& e = extensions[k];
      const std::string kind = e.target.substr(0, e.target.find(':'));
      const std::string what = e.target.substr(e.target.find(':') + 1);
      double statistic = 0;
      int tier = 1;
      std::string seen;
      if (kind == "form") {
        const auto declared = std::find_if(current.model.outputs.begin(), current.model.outputs.end(),
                                           [&](const ir::Output& o) { return o.name == what; });
        if (declared == current.model.outputs.end()) continue;
        const int derivatives = derivative_order(e.variant) - derivative_order(ir::to_string(declared->kind));
        // At the fit, else at the priors in the last tier: a fit bends the structure to follow an output of another
        // form (mdof2 with d2 a mobility: fitted, only an acceleration "fitted better"), but at priors a few per cent
        // off the truth every output's model is off by more than the noise, and multiplying it by (i w)^k "fitted
        // better" on all three outputs of a drawn spindle; ranked with the fit's evidence they crowded out the
        // calibration error its data had.
        const double at_fit = form_gain(current.channels, what, derivatives),
                     at_priors = form_gain(prior_channels_, what, derivatives);
        // And the magnitude's trend: data of another form stand (i w)^k off the model over the band, whatever the
        // resonances do (mdof2, modes damped at 0.05 % on 0.25 Hz lines: at the fit and at the priors alike the
        // peaks lay elsewhere, and chi^2 saw no form). Within a quarter of k at the priors: the last tier.
        const double slope = magnitude_slope(prior_channels_, what);
        tier = at_fit > price ? 1 : 2;
        statistic = tier == 1 ? at_fit : std::abs(slope - derivatives) < kFormSlopeTolerance ? price + 1 : at_priors;
        seen = "as its " + e.variant +
               format(", the data fit better by %.1f in chi-square (at the priors %.1f; ", at_fit, at_priors) +
               format("their magnitude's slope against the priors' %.2f decades per decade)", slope);
      } else if (kind == "swap") {
        const std::size_t comma = what.find(',');
        const std::string a = what.substr(0, comma), b = what.substr(comma + 1);
        const double at_fit = swap_gain(current.channels, a, b), at_priors = swap_gain(prior_channels_, a, b);
        statistic = std::max(at_fit, at_priors);
        seen = format("exchanged, the data fit better by %.1f in chi-square (at the priors %.1f)", at_fit, at_priors);
      } else {
        const auto selected = [&](const std::string& channel) {
          const std::size_t slash = channel.find('/');
          return kind == "gain" ? channel.substr(0, slash) == what : channel.substr(slash + 1) == what;
        };
        // At the fit, and for the sign at the priors: a fit bends the structure to follow a reversed channel (on a
        // spindle whose xh_front reads -1 times the truth, the fit put a mode 20 % off and read a factor of +0.76
        // there), the priors do not. A negative factor at the priors is taken (the polarity variant, with the priors'
        // statistic); otherwise the fit's statistic ranks: priors a few per cent off the truth raise the priors'
        // statistic on every channel alike (a drawn spindle: factors of 0.43-0.46 on all, where xs_rear alone read
        // 1.12 times the truth), and ranking by it fitted the wrong outputs.
        const GainScore at_fit = gain_score(current.channels, selected);
        const GainScore at_priors = gain_score(prior_channels_, selected);
        const GainScore& s = at_priors.factor < 0 && at_priors.statistic > price ? at_priors : at_fit;
        const auto factor = [&](const GainScore& g) { return kind == "gain" ? g.factor : 1 / g.factor; };
        seen = format("the data read %.4g times the model (score statistic %.1f; at the priors %.4g, ", factor(at_fit),
                      at_fit.statistic, factor(at_priors)) +
               format("%.1f)", at_priors.statistic);
        // A driving point that gives out power says, without any model, that its force or its sensor has the wrong
        // sign: both polarities are fitted, first, whatever the factors read. A structure fitted to reversed data
        // (every mode of a shear tower shaken at its roof, with the force's sign reversed) reads positive factors
        // at the fit and meaningless ones at priors whose modes lie elsewhere.
        const bool reversed = std::any_of(reversed_.begin(), reversed_.end(), [&](const ReversedDrivingPoint& p) {
          return (kind == "gain" ? p.output : p.input) == what;
        });
        const bool negative = e.variant == "polarity" || e.variant == "reversed";
        if (reversed && negative) {
          tier = 0;
          statistic = std::numeric_limits<double>::infinity();
          seen = "a driving point on it gives out power (the data's phase; no model needed); " + seen;
        } else {
          if (negative != (s.factor < 0)) continue;
          statistic = s.statistic;
        }
      }
      if (!(statistic > price)) continue;
      say("measurement chain: " + label(e) + ": " + seen);
      worth.push_back({tier, statistic, k});
    }
    // The candidates of the kChainFits strongest pieces of evidence are fitted (each with the variants that passed),
    // in enumeration order: by tier, then by statistic.
    std::stable_sort(worth.begin(), worth.end(), [](const Worth& a, const Worth& b) {
      return a.tier != b.tier ? a.tier < b.tier : a.statistic > b.statistic;
    });
    std::set<std::string> ids;
    for (const Worth& w : worth)
      if (ids.size() < kChainFits) ids.insert(extensions[w.index].id);
    worth.erase(std::remove_if(worth.begin(), worth.end(),
                               [&](const Worth& w) { return !ids.count(extensions[w.index].id); }),
                worth.end());
    std::sort(worth.begin(), worth.end(), [](const Worth& a, const Worth& b) { return a.index < b.index; });
    std::vector<Extension> out;
    for (const Worth& w : worth) out.push_back(std::move(extensions[w.index]));
    return out;
  }

  // The best qualifying candidate of a round, once the current model's own fit has been checked against it. A
  // candidate may win only because its search found a better optimum of the parameters it shares with the
  // current model. Re-fit the current model from the winner's estimates: if that closes the gap, the gain was a
  // better fit, not an effect; the current model improves and the candidates are judged again against it.
  int best_after_refits(DiagnosisResult& result, ModelState& current,
                        std::vector<CandidateOutcome>& outcomes, const std::vector<ModelState>& states,
                        std::size_t first_of_round) {
    int best = best_qualifying(outcomes);
    // The candidate to refit from: the qualifying winner, or, where none qualifies, the lowest BIC of all when it is
    // strongly lower. An implausible candidate far below the current model has most likely found a better optimum
    // of the parameters they share (a shear tower after its force's sign was corrected, fitted to a local optimum:
    // every added mass, none identifiable, fell by 13 000 in BIC); without the refit the current model would be
    // judged at a fit that has not converged.
    const auto source = [&]() -> int {
      if (best >= 0) return best;
      int lowest = -1;
      for (std::size_t k = 0; k < outcomes.size(); ++k)
        if (outcomes[k].error.empty() && outcomes[k].fully_fitted &&
            (lowest < 0 || outcomes[k].delta_bic < outcomes[static_cast<std::size_t>(lowest)].delta_bic))
          lowest = static_cast<int>(k);
      return lowest >= 0 && outcomes[static_cast<std::size_t>(lowest)].delta_bic < options_.min_delta_bic ? lowest : -1;
    };
    for (int guard = 0, from = source(); from >= 0 && guard < 3; ++guard, from = source()) {
      if (screen_on_companion_ && !leads_lower_on_companion(*derive_model(current.model), {},
                                                            states[static_cast<std::size_t>(from)].values,
                                                            current.values))
        break;
      ModelState refit = assess(current.model, current.text, states[static_cast<std::size_t>(from)].values,
                                options_.candidate_starts);
      if (!(refit.fit.cost < current.fit.cost * (1.0 - 1e-9))) break;
      say("the current model fits better started from the estimate of " + outcomes[static_cast<std::size_t>(from)].id +
          format(" (BIC %.1f -> %.1f): a better optimum, not an effect; judging the candidates again",
                 current.fit.bic, refit.fit.bic));
      if (result.selected.empty()) result.nominal = refit;  // the current model is still the nominal one
      current = std::move(refit);
      for (std::size_t k = 0; k < outcomes.size(); ++k) {
        CandidateOutcome& o = outcomes[k];
        if (!o.error.empty() || !o.fully_fitted) continue;
        rank_against(current, o);
        result.candidates[first_of_round + k] = o;
      }
      best = best_qualifying(outcomes);
    }
    return best;
  }

  // The selected extensions are kept only if together they explain enough (full_explanation); otherwise nothing is
  // selected, the reasons are said with the nominal findings that still show, and the current model is the nominal
  // one again.
  void keep_only_full_explanations(DiagnosisResult& result, ModelState& current) const {
    if (result.selected.empty()) return;
    const Judgement kept = full_explanation(result, current, options_);
    if (kept.holds) return;
    say(kept.why);
    for (const Discrepancy* d : kept.still)
      say("  still: " + d->text +
          format(" (band residual %.3g -> %.3g)", band_mean_z(result.nominal.channels, *d), band_mean_z(current.channels, *d)));
    result.selected.clear();
    result.explains.clear();
    current = result.nominal;
  }

  // The variants of one candidate (consecutive, one id) are one candidate: the one with the lowest BIC stands
  // for it; those that fit exactly as well (a mirror-symmetric element, which the data cannot tell apart) are
  // named with it.
  static void keep_best_variants(std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states) {
    std::vector<CandidateOutcome> kept_outcomes;
    std::vector<ModelState> kept_states;
    for (std::size_t first = 0; first < outcomes.size();) {
      std::size_t end = first + 1;
      while (end < outcomes.size() && outcomes[end].id == outcomes[first].id) ++end;
      // Fully fitted variants before screened-out ones before failed ones, and among fully fitted the plausible
      // ones first (a richer variant whose parameters the data cannot determine does not stand for the candidate
      // when a plausible one exists); within a tier, the lowest BIC, and of variants that fit exactly as well the
      // one with fewer new parameters (a force reversed rather than reversed and scaled, where the structure's
      // scale takes up the scale: BIC counts only the parameters the data determine, so the two tie).
      const auto tier = [&](std::size_t k) {
        return !outcomes[k].error.empty() ? 3 : !outcomes[k].fully_fitted ? 2 : outcomes[k].plausible ? 0 : 1;
      };
      const auto simpler = [&](std::size_t a, std::size_t b) {
        return outcomes[a].new_parameters.size() < outcomes[b].new_parameters.size();
      };
      std::size_t best = first;
      for (std::size_t k = first; k < end; ++k)
        if (tier(k) < tier(best) ||
            (tier(k) == tier(best) && tier(k) <= 1 &&
             (outcomes[k].delta_bic < outcomes[best].delta_bic - thresholds::kBicTie ||
              (outcomes[k].delta_bic <= outcomes[best].delta_bic + thresholds::kBicTie && simpler(k, best)))))
          best = k;
      CandidateOutcome o = outcomes[best];
      o.variants_tried = static_cast<int>(end - first);
      for (std::size_t k = first; k < end; ++k)
        if (k != best && tier(k) == tier(best) && tier(k) <= 1 &&
            std::abs(outcomes[k].delta_bic - o.delta_bic) <= thresholds::kBicTie)
          o.equivalent_variants.push_back(outcomes[k].variant);
      if (!o.equivalent_variants.empty()) {
        std::string names;
        for (const std::string& v : o.equivalent_variants) names += (names.empty() ? "" : ", ") + v;
        o.description += " (" + names + " instead fits exactly as well: the data cannot tell them apart)";
      }
      kept_outcomes.push_back(std::move(o));
      kept_states.push_back(std::move(states[best]));
      first = end;
    }
    outcomes = std::move(kept_outcomes);
    states = std::move(kept_states);
  }

  // Names of other qualifying candidates that fit exactly as well as `best` (equivalent extensions).
  static std::vector<std::string> equivalents(const std::vector<CandidateOutcome>& outcomes, int best) {
    std::vector<std::string> out;
    for (std::size_t k = 0; k < outcomes.size(); ++k)
      if (static_cast<int>(k) != best && outcomes[k].qualifies &&
          std::abs(outcomes[k].delta_bic - outcomes[static_cast<std::size_t>(best)].delta_bic) <= thresholds::kBicTie)
        out.push_back(outcomes[k].id);
    return out;
  }

  // Under the fits' progress lock: a candidate's line may come while another candidate's fit reports progress.
  void say(const std::string& line) const {
    std::lock_guard<std::mutex> lock(fit_progress_mutex_);
    if (options_.progress) options_.progress(line);
  }

  // Peaks of the measured FRFs that no peak of the model at its prior values accounts for (none within 8 %),
  // strongest first. A fit can hide a missing mode by bending other parameters (a soft mount standing in for a
  // compliant base), so the fitted residual alone may not point at it; the data's own peaks against the prior
  // model do.
  // Also fills prior_output_peaks_: the same per output, down to a lower prominence (3 dB, not 6: a sensor's
  // mounting resonance is damped, 5 % and more, and near 1 kHz the spindle's xs_front rises less than 5 dB at it),
  // the output's own peaks first. A peak that no other output shows is what a sensor's own resonance looks like;
  // a structural mode shows on every output that moves with it. The own peaks go by prominence, not height: a
  // displacement FRF falls with frequency, so height would favour a low wiggle over a clear peak at 1 kHz.
  std::vector<double> prior_peaks(const ir::ModelIr& model) {
    const auto evaluator = derive_model(model);
    std::vector<std::pair<double, double>> found;  // (magnitude relative to the channel's RMS, f)
    struct OutputPeak {
      double height;         // relative to the channel's RMS
      double prominence_db;
      double f;
    };
    std::map<std::string, std::vector<OutputPeak>> by_output;
    prior_channels_ =
        channel_residuals(*evaluator, data_, evaluator->info().default_values(), options_.fit.frf_weighting);
    for (const ChannelResidual& c : prior_channels_) {
      if (c.measured.size() == 0) continue;  // no line stands out of the noise (a few lines only): nothing to find
      const std::vector<int> model_peaks = magnitude_peaks(c.model);
      const double rms = std::sqrt(c.measured.cwiseAbs2().mean());
      const auto unexplained = [&](double f) {
        return std::none_of(model_peaks.begin(), model_peaks.end(), [&](int m) {
          return std::abs(c.f_hz[static_cast<std::size_t>(m)] - f) <= thresholds::kPriorPeakMatch * f;
        });
      };
      // One scan for both lists: the 6 dB peaks are among the 3 dB ones.
      for (int i = 1; i + 1 < static_cast<int>(c.measured.size()); ++i) {
        const double prominence = peak_prominence_db(c.measured, i);
        const double f = c.f_hz[static_cast<std::size_t>(i)];
        if (prominence < thresholds::kPeakProminenceDb || !unexplained(f)) continue;
        // The rise must stand out of the noise too (4 standard deviations): in data near the noise level, noise
        // alone makes wiggles of several dB.
        const double magnitude = std::abs(c.measured[i]);
        const double rise = magnitude * (1.0 - std::pow(10.0, -prominence / 20.0));
        if (rise < thresholds::kPeakNoiseSigmas * c.sigma[i]) continue;
        const double height = std::abs(c.measured[i]) / rms;
        if (prominence >= thresholds::kStrongPeakProminenceDb) found.emplace_back(height, f);
        by_output[output_of(c.channel)].push_back({height, prominence, f});
      }
    }
    prior_output_peaks_.clear();
    for (const auto& entry : by_output) {
      const std::string& output = entry.first;  // a named variable, not a structured binding: lambdas capture it
      std::vector<std::pair<double, double>> own, shared;  // (prominence, f) and (height, f)
      for (const OutputPeak& peak : entry.second) {
        const bool elsewhere = std::any_of(by_output.begin(), by_output.end(), [&](const auto& other) {
          return other.first != output && std::any_of(other.second.begin(), other.second.end(), [&](const OutputPeak& q) {
                   return std::abs(q.f - peak.f) <= thresholds::kSamePeak * peak.f;
                 });
        });
        if (elsewhere)
          shared.emplace_back(peak.height, peak.f);
        else
          own.emplace_back(peak.prominence_db, peak.f);
      }
      std::vector<double> peaks = strongest_first(own);
      for (double f : strongest_first(shared)) add_distinct(peaks, f);
      prior_output_peaks_[output] = peaks;
    }
    return strongest_first(found);
  }

  static std::string output_of(const std::string& channel) { return channel.substr(0, channel.find('/')); }

  // The outputs the model misses more than all others (see context()): mean excess over the noise above 0.5 and
  // at least twice every other output's.
  static std::set<std::string> outputs_missed_alone(const std::vector<ChannelResidual>& channels) {
    std::map<std::string, std::pair<double, long>> sums;  // output -> (sum of z, lines)
    for (const ChannelResidual& c : channels)
      for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
        auto& s = sums[output_of(c.channel)];
        s.first += normalized_residual(c.measured[k], c.model[k], c.sigma[k]);
        ++s.second;
      }
    std::map<std::string, double> excess;
    for (const auto& [output, s] : sums)
      if (s.second > 0) excess[output] = s.first / static_cast<double>(s.second) - 1.0;
    std::set<std::string> out;
    for (const auto& [output, e] : excess) {
      bool alone = e > thresholds::kSensorAloneExcess;
      for (const auto& [other, f] : excess)
        if (other != output && !(e >= thresholds::kSensorAloneRatio * f)) alone = false;
      if (alone) out.insert(output);
    }
    return out;
  }

  // Appends f to `peaks` unless one already there is within 2 % of it (the same peak, seen again).
  static void add_distinct(std::vector<double>& peaks, double f) {
    if (std::none_of(peaks.begin(), peaks.end(),
                     [&](double g) { return std::abs(f - g) <= thresholds::kSamePeak * f; }))
      peaks.push_back(f);
  }

  // Frequencies of (strength, f) pairs, strongest first, those within 2 % of a stronger one left out.
  static std::vector<double> strongest_first(std::vector<std::pair<double, double>> found) {
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<double> peaks;
    for (const auto& [strength, f] : found) add_distinct(peaks, f);
    return peaks;
  }

  // Peaks for new parameters' start values: first the data's peaks that the prior model does not account for
  // (strongest first: the most direct evidence of a missing mode), then the fitted model's unexplained resonances.
  ExtensionContext context(const ModelState& s) const {
    ExtensionContext ctx;
    for (double f : prior_peaks_) add_distinct(ctx.peak_hz, f);
    ctx.output_peak_hz = prior_output_peaks_;
    for (const Discrepancy& d : s.residual.discrepancies)  // already strongest first
      if (d.kind == "unexplained_resonance") {
        add_distinct(ctx.peak_hz, d.f_hz);
        add_distinct(ctx.output_peak_hz[output_of(d.channel)], d.f_hz);
      }
    ctx.varying_parameters = varying_parameters(data_);
    ctx.values = s.values;
    // What a sensor's own dynamics could explain: an output whose channels the model misses more than it misses
    // the others'. A sensor or its signal chain changes one output only; a discrepancy every output shows belongs
    // to the structure. Judged on the nominal model, before extensions reshape the residual: an output whose mean
    // excess over the noise (mean normalized residual minus 1) is above 0.5 and at least twice every other
    // output's. (A filter's phase spread thinly over the band may raise no band above the threshold, hence the
    // mean; on the spindle with a Maxwell element in a bearing, which every output shows, a low-pass on xs_front
    // joined a soft mount to "explain" 4 of its 9 findings.) In later rounds the output must also be the one the
    // current model misses alone: once an extension has taken up the structure's part, what is left on one output
    // is a sensor's only if it stands out there (mdof2 with a Maxwell element at the wall, from a record: a
    // compliant wall, then a delay on d1 "explained" what the wall left on both outputs).
    const std::set<std::string> now = outputs_missed_alone(s.channels);
    for (const std::string& o : sensor_outputs_)
      if (now.count(o)) ctx.outputs_with_findings.insert(o);
    for (const Discrepancy& d : s.residual.discrepancies)
      if (d.kind == "phase_trend" && !ctx.output_delay_s.count(output_of(d.channel)))
        ctx.output_delay_s[output_of(d.channel)] = d.delay_s;
    for (const ChannelResidual& c : s.channels) {
      if (c.f_hz.empty()) continue;
      ctx.band_lo_hz = ctx.band_lo_hz > 0 ? std::min(ctx.band_lo_hz, c.f_hz.front()) : c.f_hz.front();
      ctx.band_hi_hz = std::max(ctx.band_hi_hz, c.f_hz.back());
    }
    return ctx;
  }

  // Derives every candidate, fits those that are not the same model as an earlier one (same_response.hpp) on
  // worker threads, and gives each of the others the fit of its twin. Outcomes and states are in the order of
  // `extensions`, and so are the progress lines.
  void score_all(const std::vector<Extension>& extensions, const ModelState& base, int round,
                 std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states) const {
    const std::size_t n = extensions.size();
    std::vector<std::unique_ptr<mbgen::Model>> evaluators(n);
    std::vector<std::string> derive_errors(n);
    std::vector<int> twin(n, -1);  // an earlier candidate that is the same model
    std::set<std::string> names_in_use;
    for (const auto& entry : base.values) names_in_use.insert(entry.first);
    for (const auto& entry : options_.set) names_in_use.insert(entry.first);
    for (const DataSet& d : data_)
      for (const auto& entry : d.set()) names_in_use.insert(entry.first);
    const std::vector<double> probes = probe_frequencies(data_);
    for (std::size_t k = 0; k < n; ++k) {
      try {
        evaluators[k] = derive_model(extensions[k].model);
      } catch (const std::exception& e) {
        derive_errors[k] = e.what();
        continue;
      }
      for (std::size_t j = 0; j < k && twin[k] < 0; ++j)
        if (evaluators[j] && twin[j] < 0 && same_response(*evaluators[j], *evaluators[k], probes, names_in_use))
          twin[k] = static_cast<int>(j);
    }
    std::vector<std::size_t> fitted;  // the candidates fitted in their own right
    for (std::size_t k = 0; k < n; ++k)
      if (evaluators[k] && twin[k] < 0) fitted.push_back(k);
    std::vector<std::shared_ptr<estimation::LocalFitMemo>> memos(n);
    for (std::size_t k : fitted) memos[k] = make_local_fit_memo();
    std::vector<char> screened_out(n, 0);
    outcomes.assign(n, CandidateOutcome{});
    states.assign(n, ModelState{});
    screen(extensions, evaluators, memos, base, round, fitted, outcomes, states, screened_out);
    fitted.erase(std::remove_if(fitted.begin(), fitted.end(), [&](std::size_t k) { return screened_out[k] != 0; }),
                 fitted.end());
    // Candidates side by side (each fit on one thread) keep the cores busy through a fit's serial stretches; a core
    // that finds no candidate left joins the starts of the fits still running.
    const Workers workers{1, std::make_shared<ThreadBudget>(options_.fit.threads), nullptr};
    std::size_t said = 0;
    const auto say_done_up_to = [&](std::size_t end) {
      for (; said < end; ++said) {
        const Extension& ext = extensions[said];
        const CandidateOutcome& o = outcomes[said];
        const std::string as = twin[said] < 0 ? "" : "  (the same model as " + label(extensions[twin[said]]) + ")";
        const std::string result =
            !o.error.empty()   ? "failed: " + o.error
            : !o.fully_fitted  ? format("screened out (screening delta BIC %.1f", o.screen_delta_bic) +
                                    (has_records_ ? format(", on the records %.1f)", o.screen_records_delta_bic) : ")")
                               : fitted_text(o);
        say(format("[%.0f/%.0f] ", static_cast<double>(said + 1), static_cast<double>(n)) + label(ext) + ": " + result +
            as);
      }
    };
    // Finishing candidate fitted[i] settles every candidate before fitted[i + 1]: those derived from it or failed.
    const auto settle = [&](std::size_t k) {
      if (screened_out[k]) return;  // its outcome is the screening's
      if (!evaluators[k]) {
        outcomes[k] = failed(extensions[k], round, derive_errors[k]);
      } else if (twin[k] >= 0) {
        const std::size_t j = static_cast<std::size_t>(twin[k]);
        if (!outcomes[j].error.empty()) {
          outcomes[k] = failed(extensions[k], round, outcomes[j].error);
        } else if (screened_out[j]) {
          outcomes[k] = outcomes[j];
          const CandidateOutcome frame = outline(extensions[k], round);
          outcomes[k].id = frame.id, outcomes[k].description = frame.description, outcomes[k].variant = frame.variant;
          outcomes[k].new_parameters = frame.new_parameters, outcomes[k].freed_parameters = frame.freed_parameters;
          states[k] = renamed(states[j], extensions[k], evaluators[k]->info());
        } else {
          states[k] = renamed(states[j], extensions[k], evaluators[k]->info());
          outcomes[k] = judge(extensions[k], *evaluators[k], states[k], base, round);
        }
      }
    };
    const std::size_t first_fitted = fitted.empty() ? n : fitted.front();
    for (std::size_t k = 0; k < first_fitted; ++k) settle(k);
    say_done_up_to(first_fitted);
    ordered_parallel(
        fitted.size(), *workers.cores,
        [&](std::size_t i) {
          const std::size_t k = fitted[i];
          const double screened = outcomes[k].screen_delta_bic, on_records = outcomes[k].screen_records_delta_bic;
          outcomes[k] =
              score(extensions[k], *evaluators[k], base, round, Workers{1, workers.cores, memos[k]}, states[k]);
          outcomes[k].screen_delta_bic = screened;
          outcomes[k].screen_records_delta_bic = on_records;
        },
        [&](std::size_t i) {
          const std::size_t end = i + 1 < fitted.size() ? fitted[i + 1] : n;
          for (std::size_t k = fitted[i] + 1; k < end; ++k) settle(k);
          say_done_up_to(end);
        });
    for (std::size_t k : fitted)
      if (refit_from_sibling(extensions, evaluators, memos, base, round, k, outcomes, states))
        for (std::size_t t = k + 1; t < n; ++t)
          if (twin[t] == static_cast<int>(k)) settle(t);
  }

  // Extension::start_from_variant: candidate k and the sibling variant it names both fully fitted; k is searched
  // once more around where the sibling ended (two starts; with records searched on their H1 estimates and refined
  // on the records, as every search; the parameters it holds held as before), and takes that fit if its cost is
  // lower. True when it did.
  bool refit_from_sibling(const std::vector<Extension>& extensions,
                          const std::vector<std::unique_ptr<mbgen::Model>>& evaluators,
                          const std::vector<std::shared_ptr<estimation::LocalFitMemo>>& memos, const ModelState& base,
                          int round, std::size_t k, std::vector<CandidateOutcome>& outcomes,
                          std::vector<ModelState>& states) const {
    const Extension& ext = extensions[k];
    const Extension::VariantStart& from = ext.start_from_variant;
    if (from.variant.empty() || !outcomes[k].fully_fitted || !outcomes[k].error.empty()) return false;
    std::size_t j = extensions.size();
    for (std::size_t i = 0; i < extensions.size(); ++i)
      if (i != k && extensions[i].id == ext.id && extensions[i].variant == from.variant) j = i;
    if (j == extensions.size() || !outcomes[j].fully_fitted || !outcomes[j].error.empty()) return false;
    std::map<std::string, double> start;
    const ModelInfo& info = evaluators[k]->info();
    for (const auto& [name, v] : states[j].values)
      if (info.parameter_index(name) >= 0) start[name] = v;
    for (const auto& [mine, theirs] : from.from) {
      const auto it = states[j].values.find(theirs.first);
      if (it != states[j].values.end()) start[mine] = theirs.second * it->second;
    }
    if (!leads_lower_on_companion(*evaluators[k], states[k].held, start, states[k].values)) return false;
    ModelState state;
    try {
      state = assess(*evaluators[k], ext.model, ext.mdl_text, start, 2,
                     Workers{options_.fit.threads, nullptr, memos[k]}, {}, states[k].held);
    } catch (const std::exception&) {
      return false;  // not fitted from there: the candidate's own fit stands
    }
    if (!(state.fit.cost < states[k].fit.cost)) return false;
    CandidateOutcome o = judge(ext, *evaluators[k], state, base, round);
    o.screen_delta_bic = outcomes[k].screen_delta_bic;
    o.screen_records_delta_bic = outcomes[k].screen_records_delta_bic;
    say(label(ext) + ": started from the " + from.variant + " variant's estimate it fits better: " + fitted_text(o));
    outcomes[k] = std::move(o);
    states[k] = std::move(state);
    return true;
  }

  // Screening (DiagnoseOptions::full_fits): cheaper fits of every candidate, ranked by BIC against the current
  // model fitted the same way; candidates outside the `full_fits` best are screened out: their outcome is the
  // screening fit, and they cannot qualify. Fills `screen_delta_bic` of every candidate in `fitted`.
  //  - On FRFs (the measured ones, or the records' H1 estimates: no simulation): a candidate that contains the
  //    current model (Extension::nesting) descends from the point where it is the current model, once, to
  //    convergence (the score test carried through); any other, two local fits to convergence, from the current
  //    estimate and from the priors (the centres of the full fit's two searches, without its random starts,
  //    validation or residual analysis), and one from each of the candidate's alternative starts.
  //  - With time records also a few Gauss-Newton steps on the records from the current estimate: an effect the
  //    records show but their H1 estimates' coarse lines blur (the gyroscopic split of the spindle's modes at
  //    300 rev/s, a few Hz under 8 Hz lines: screening delta BIC +17.9 on the H1 estimates, -20681 fitted on the
  //    records) shows in the time-domain cost at once. The kept candidates alternate between the two rankings.
  void screen(const std::vector<Extension>& extensions, const std::vector<std::unique_ptr<mbgen::Model>>& evaluators,
              const std::vector<std::shared_ptr<estimation::LocalFitMemo>>& memos, const ModelState& base, int round,
              const std::vector<std::size_t>& fitted,
              std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states,
              std::vector<char>& screened_out) const {
    if (options_.full_fits <= 0 || static_cast<int>(fitted.size()) <= options_.full_fits) return;
    const std::unique_ptr<mbgen::Model> base_model = derive_model(base.model);
    const auto cores = std::make_shared<ThreadBudget>(options_.fit.threads);
    enum class Kind { Spectral, Records };
    const auto screening_fit = [&](const mbgen::Model& evaluator, const Extension* ext, Kind kind,
                                   const std::shared_ptr<estimation::LocalFitMemo>& memo) {
      const bool is_base = ext == nullptr;
      FitOptions fo = options_.fit;
      const ModelInfo& info = evaluator.info();
      fo.values = estimated_values(info, base.values);
      fo.also_start_at.clear();
      fo.optimum_start_at.clear();
      fo.further_starts_at.clear();
      fo.threads = 1;
      fo.cores = cores;
      fo.progress = nullptr;
      fo.memo = memo;
      if (kind == Kind::Records) {
        fo.starts = 1;
        fo.spectral_search = false;
        fo.max_iterations = 3;
        return fit(evaluator, split_.fit, fo);
      }
      fo.frf_weighting.averages = std::max(fo.frf_weighting.averages, screen_averages_);
      // A candidate that contains the current model (Extension::nesting) is screened near the current estimate
      // only: from its new parameters' start values and from the point where it is the current model again.
      // Descending from that point is the score test carried to convergence (its first step is the Gauss-Newton step
      // whose predicted gain is the Lagrange-multiplier statistic; the cost can only fall below the current
      // model's); the other start finds what a score test cannot see, an effect of second order at the nesting
      // point (a mount's stiffness untied from its mirror image: x-direction data see only the pair's sum until
      // the asymmetry couples the planes). The searches from the priors and the alternative starts are the full
      // fit's.
      if (!is_base && !ext->nesting.empty()) {
        fo.starts = 2;
        fo.optimum_start_at = ext->nesting;
        return fit(evaluator, screen_data_, fo);
      }
      // Converged local fits: cut to 40 or 100 iterations, or stopped after the log-ratio search, the compliant
      // base of the spindle's base-mode data ranked below the six kept (screening delta BIC +359 against -15103).
      fo.starts = is_base ? 1 : 2;
      if (!is_base) {
        for (const ParameterInfo& p : info.parameters) fo.also_start_at[p.name] = p.value;
        fo.further_starts_at = ext->alternative_starts;
        fo.starts += static_cast<int>(fo.further_starts_at.size());
      }
      return fit(evaluator, screen_data_, fo);
    };
    const std::vector<Kind> kinds = has_records_ ? std::vector<Kind>{Kind::Spectral, Kind::Records}
                                                 : std::vector<Kind>{Kind::Spectral};
    std::vector<double> base_bic, base_cost;
    for (Kind kind : kinds) {
      const FitResult r =
          kind == Kind::Spectral && !has_records_ ? base.fit : screening_fit(*base_model, nullptr, kind, nullptr);
      base_bic.push_back(r.bic);
      base_cost.push_back(r.cost);
    }
    const std::size_t n = extensions.size();
    std::vector<std::vector<double>> bic(kinds.size(), std::vector<double>(n, std::numeric_limits<double>::infinity()));
    ordered_parallel(
        fitted.size(), *cores,
        [&](std::size_t i) {
          const std::size_t k = fitted[i];
          for (std::size_t t = 0; t < kinds.size(); ++t) {
            try {
              FitResult r = screening_fit(*evaluators[k], &extensions[k], kinds[t], memos[k]);
              bic[t][k] = r.bic;
              if (t > 0) continue;
              ModelState& s = states[k];
              s.model = extensions[k].model;
              s.text = extensions[k].mdl_text;
              s.info = evaluators[k]->info();
              s.values = values_by_name(s.info, r.values);
              s.fit = std::move(r);
            } catch (const std::exception&) {
              bic[t][k] = -std::numeric_limits<double>::infinity();  // fitted fully, where a failure is reported
            }
          }
        },
        [](std::size_t) {});
    // The kept: the best of each ranking in turn.
    std::vector<std::vector<std::size_t>> orders;
    for (std::size_t t = 0; t < kinds.size(); ++t) {
      std::vector<std::size_t> order = fitted;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bic[t][a] < bic[t][b]; });
      orders.push_back(order);
    }
    // Only a candidate whose screening shows evidence goes on: a BIC below the current model's by more than
    // |min_delta_bic| in one of the rankings (a failed screening fit too, whose failure the full fit reports). For a
    // candidate that contains the current model the screening fit is the score test carried to convergence: without
    // evidence there, the full fit could only find a distant optimum, and a later round on a model near the noise
    // spent most of its time fitting candidates that all ended above it.
    const auto evidence = [&](std::size_t k) {
      for (std::size_t t = 0; t < kinds.size(); ++t)
        if (!(bic[t][k] - base_bic[t] >= options_.min_delta_bic)) return true;
      return false;
    };
    std::set<std::size_t> kept;
    for (std::size_t r = 0; kept.size() < static_cast<std::size_t>(options_.full_fits) && r < fitted.size(); ++r)
      for (std::size_t t = 0; t < kinds.size() && kept.size() < static_cast<std::size_t>(options_.full_fits); ++t)
        if (evidence(orders[t][r])) kept.insert(orders[t][r]);
    // A candidate's variants are forms of one explanation, which the full fits choose among. A variant whose
    // screening fits all ended above the current model's cost, a point every candidate contains (in a limit: a
    // rigid support, a vanishing resonator), has not been judged but failed to fit: it goes on to the full fit when
    // a sibling variant does. (A spindle base at 188 Hz: the simple variant's screening ended at delta BIC +7291
    // and only the on-feet variant was kept, which leaves a clear misfit; fully fitted, the simple variant names it.)
    std::set<std::string> kept_ids;
    for (std::size_t k : kept) kept_ids.insert(extensions[k].id);
    for (std::size_t k : fitted)
      if (!extensions[k].variant.empty() && kept_ids.count(extensions[k].id) && std::isfinite(bic[0][k]) &&
          states[k].fit.cost > base_cost[0])
        kept.insert(k);
    for (std::size_t k : fitted) {
      outcomes[k].screen_delta_bic = bic[0][k] - base_bic[0];
      if (kinds.size() > 1) outcomes[k].screen_records_delta_bic = bic[1][k] - base_bic[1];
    }
    for (std::size_t k : fitted) {
      if (kept.count(k) || !std::isfinite(bic[0][k])) continue;
      screened_out[k] = 1;
      CandidateOutcome o = outline(extensions[k], round);
      o.fit = states[k].fit;
      o.validation_nrmse = std::numeric_limits<double>::quiet_NaN();
      o.delta_bic = std::numeric_limits<double>::quiet_NaN();
      o.screen_delta_bic = outcomes[k].screen_delta_bic;
      o.screen_records_delta_bic = outcomes[k].screen_records_delta_bic;
      o.fully_fitted = false;
      o.doubts.push_back(evidence(k) ? format("screened out: its screening fits ranked below the %.0f best",
                                              static_cast<double>(options_.full_fits))
                                     : format("screened out: its screening fits lower no BIC by more than %.0f",
                                              -options_.min_delta_bic));
      outcomes[k] = std::move(o);
    }
  }

  // A fully fitted candidate's result on its progress line.
  static std::string fitted_text(const CandidateOutcome& o) {
    return format("delta BIC %.1f, validation %.4g", o.delta_bic, o.validation_nrmse) +
           (o.qualifies ? "  (qualifies)" : "") + doubts_text(o);
  }

  // Why a fully fitted candidate is not plausible, for its progress line.
  static std::string doubts_text(const CandidateOutcome& o) {
    if (o.plausible || o.doubts.empty()) return {};
    std::string out = "  (implausible: ";
    for (std::size_t i = 0; i < o.doubts.size(); ++i) out += (i ? "; " : "") + o.doubts[i];
    return out + ")";
  }

  static std::string label(const Extension& ext) {
    return ext.id + (ext.variant.empty() ? "" : " (" + ext.variant + ")");
  }

  static CandidateOutcome failed(const Extension& ext, int round, const std::string& error) {
    CandidateOutcome o = outline(ext, round);
    o.error = error;
    return o;
  }

  static CandidateOutcome outline(const Extension& ext, int round) {
    CandidateOutcome o;
    o.id = ext.id;
    o.description = ext.description;
    o.variant = ext.variant;
    o.round = round;
    o.new_parameters = ext.new_parameters;
    o.freed_parameters = ext.freed_parameters;
    return o;
  }

  // The state of a twin candidate, carried over to `ext`: its model, and its parameters' names by position.
  static ModelState renamed(const ModelState& twin, const Extension& ext, const ModelInfo& info) {
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

  CandidateOutcome score(const Extension& ext, const mbgen::Model& evaluator, const ModelState& base, int round,
                         const Workers& workers, ModelState& state) const {
    try {
      state = search(ext, evaluator, base, workers, {});
      // New parameters the data cannot determine are held at their start values and the rest fitted again: on a
      // base on feet whose rocking about one axis the x-direction data barely see, that rocking's inertia ran to a
      // bound and took the base's depth and two foot constants with it ("not identifiable"), though the fit was
      // at the noise level. Holding some may leave others undetermined (what they were determined through): at
      // most three reductions; what is left undetermined then is judged as it is.
      std::vector<std::string> held;
      for (int reduction = 0; reduction < 3; ++reduction) {
        const std::vector<std::string> more = undetermined_new_parameters(ext, state.fit);
        if (more.empty() || held.size() + more.size() >= ext.new_parameters.size()) break;
        held.insert(held.end(), more.begin(), more.end());
        try {
          state = search(ext, evaluator, base, workers, held);
        } catch (const std::exception&) {
          break;  // the reduced model could not be fitted or judged: the last fit stands
        }
      }
      return judge(ext, evaluator, state, base, round);
    } catch (const std::exception& e) {
      return failed(ext, round, e.what());
    }
  }

  // A candidate's fit: two searches, around the current estimate and around the priors (where the current
  // estimate has bent parameters to mimic the missing effect, the priors are the better start); the lower cost
  // wins. With time records one search starts from both (also_start_at): each search ends in simulation-based
  // refinements of its best start and of its centre, which cost most of a candidate's time, so the priors get a
  // start of the search rather than a search of their own. `held`: new parameters kept at their start values.
  // Each search also starts from the candidate's alternative starts (its new mode at the next peaks).
  ModelState search(const Extension& ext, const mbgen::Model& evaluator, const ModelState& base,
                    const Workers& workers, const std::vector<std::string>& held) const {
    const std::vector<std::map<std::string, double>>& further = ext.alternative_starts;
    if (has_records_) {
      std::map<std::string, double> priors;
      for (const ParameterInfo& p : evaluator.info().parameters) priors[p.name] = p.value;
      return assess(evaluator, ext.model, ext.mdl_text, base.values, options_.candidate_starts + 1, workers, priors,
                    held, further, ext.nesting);
    }
    ModelState s =
        assess(evaluator, ext.model, ext.mdl_text, base.values, options_.candidate_starts, workers, {}, held, further,
               ext.nesting);
    ModelState from_priors =
        assess(evaluator, ext.model, ext.mdl_text, {}, options_.candidate_starts, workers, {}, held, further);
    if (from_priors.fit.cost < s.fit.cost) s = std::move(from_priors);
    return s;
  }

  // The candidate's new parameters that its fit could not determine: not identifiable or known to no better than
  // 50 % (judge_plausibility's measures), and not held against a bound by the data (a parameter pressed against a
  // bound is a doubt of its own).
  static std::vector<std::string> undetermined_new_parameters(const Extension& ext, const FitResult& fit) {
    std::vector<std::string> out;
    for (const NewParameter& np : ext.new_parameters)
      for (const ParameterEstimate& p : fit.parameters)
        if (p.name == np.name && p.pull_chi2 <= thresholds::kBoundPullChi2 &&
            (!p.identifiable || p.std > thresholds::kPoorlyDetermined * std::abs(p.value)))
          out.push_back(p.name);
    return out;
  }

  // The outcome of a fitted candidate against the current model `base`.
  CandidateOutcome judge(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s,
                         const ModelState& base, int round) const {
    CandidateOutcome o = outline(ext, round);
    o.fit = s.fit;
    o.validation_nrmse = s.validation_nrmse;
    o.held_parameters = s.held;
    if (!s.held.empty()) {
      std::string names;
      for (const std::string& n : s.held) names += (names.empty() ? "" : ", ") + n;
      o.description += " (the data do not determine " + names + ": held at " + (s.held.size() > 1 ? "their" : "its") +
                       " start value" + (s.held.size() > 1 ? "s" : "") + ")";
    }
    if (ext.operator_name == kChainOperator)
      o.description = chain_description(ext, s.fit, o.description,
                                        ext.new_parameters.size() == 1 &&
                                            scale_confounded(evaluator, s, ext.new_parameters[0].name));
    judge_plausibility(ext, s.info, o);
    judge_new_body_modes(ext, evaluator, s, o);
    o.plausible = o.doubts.empty();
    rank_against(base, o);
    return o;
  }

  // A chain candidate's description with its estimate: "xs_rear reads 0.8012 +- 0.0031 times the structure's motion
  // (...)", naming a unit mix-up when the factor is one (mm read as m, g as m/s^2, and back).
  // Whether the data cannot tell parameter `name`'s size from the structure's scale: doubling every other estimated
  // parameter and doubling or halving this one leaves every FRF of the model as it is (a force's factor where every
  // mass, stiffness and damping is estimated, or the factor of a model's only output). Checked on the model's FRFs at
  // a few of the data's lines; a fit then holds some parameter or stops at a bound, and the factor's size and std it
  // reports are only relative to that.
  static bool scale_confounded(const mbgen::Model& evaluator, const ModelState& s, const std::string& name) {
    const ModelInfo& info = evaluator.info();
    const int g = info.parameter_index(name);
    if (g < 0 || s.channels.empty() || s.channels.front().f_hz.empty()) return false;
    const std::vector<double>& lines = s.channels.front().f_hz;
    std::vector<double> f;
    for (std::size_t k = 0; k < 8; ++k) f.push_back(lines[k * (lines.size() - 1) / 7]);
    try {
      const Eigen::VectorXd p = s.fit.values;
      const FrfResult at = frf(evaluator, p, f);
      for (double factor : {2.0, 0.5}) {
        Eigen::VectorXd q = p;
        for (std::size_t i = 0; i < info.parameters.size(); ++i)
          if (info.parameters[i].role == ParameterRole::Estimate && static_cast<int>(i) != g)
            q[static_cast<Eigen::Index>(i)] *= 2.0;
        q[g] *= factor;
        const FrfResult scaled = frf(evaluator, q, f);
        double worst = 0;
        for (std::size_t k = 0; k < f.size(); ++k)
          worst = std::max(worst, (scaled.H[k] - at.H[k]).norm() / std::max(at.H[k].norm(), 1e-300));
        if (worst < 1e-8) return true;
      }
    } catch (const std::exception&) {
    }
    return false;
  }

  static std::string chain_description(const Extension& ext, const FitResult& fit, const std::string& otherwise,
                                       bool size_confounded) {
    if (ext.new_parameters.size() != 1) return otherwise;
    const auto it = std::find_if(fit.parameters.begin(), fit.parameters.end(),
                                 [&](const ParameterEstimate& p) { return p.name == ext.new_parameters[0].name; });
    if (it == fit.parameters.end()) return otherwise;
    const double g = it->value, sd = it->identifiable ? it->std : 0.0;
    const std::string what = ext.target.substr(ext.target.find(':') + 1);
    const bool input = ext.target.rfind("input:", 0) == 0;
    if (size_confounded) {
      const std::string size = "; its size the data cannot tell from the structure's scale";
      if (g < 0)
        return (input ? "the recorded " + what + " has the opposite sign of the force applied (a reaction force taken "
                                                   "with the wrong sign)"
                      : what + " reads with the opposite sign: the sensor is mounted or wired reversed") +
               size;
      return (input ? "the recorded " + what + " is a constant factor of the force applied" : what + " reads a constant "
                                                                                                  "factor of the motion") +
             size;
    }
    std::string text = (input ? "the recorded " + what + " is " : what + " reads ") + format("%.4g", g) +
                       (sd > 0 ? format(" +- %.2g", sd) : "") +
                       (input ? " times the force applied" : " times the structure's motion");
    struct Unit {
      double factor;
      const char* name;
    };
    static const Unit kUnits[] = {{1e3, "millimetres read as metres"}, {1e-3, "metres read as millimetres"},
                                  {1 / 9.80665, "m/s^2 read as g"}, {9.80665, "g read as m/s^2"}};
    for (const Unit& u : kUnits) {
      const double factor = input ? 1 / u.factor : u.factor;
      if (std::abs(std::abs(g) - factor) <= std::max(3 * sd, 0.01 * factor))
        return text + ": a unit mix-up, " + u.name + (g < 0 ? ", and the sign reversed" : "");
    }
    if (g < 0)
      return text + (input ? ": its sign is reversed (a reaction force taken with the wrong sign)"
                           : ": the sensor is mounted or wired reversed");
    return text + (input ? ": the force transducer's calibration" : ": its sensor's calibration");
  }

  // ΔBIC against the current model `base`, and whether the evidence is strong: BIC, validation and plausibility.
  void rank_against(const ModelState& base, CandidateOutcome& o) const {
    o.delta_bic = o.fit.bic - base.fit.bic;
    o.qualifies = o.plausible && o.delta_bic < options_.min_delta_bic &&
                  o.validation_nrmse < (1.0 - options_.min_validation_gain) * base.validation_nrmse;
  }

  // New (and freed) parameters must be determined by the data and physically sensible: identifiable, known to
  // better than 50 %, and not pressed against a bound (the optimum would lie beyond what is physical).
  static void judge_plausibility(const Extension& ext, const ModelInfo& info, CandidateOutcome& o) {
    std::vector<std::string> names = o.freed_parameters;
    for (const NewParameter& p : ext.new_parameters) names.push_back(p.name);
    for (const std::string& name : names) {
      const auto it = std::find_if(o.fit.parameters.begin(), o.fit.parameters.end(),
                                   [&](const ParameterEstimate& p) { return p.name == name; });
      if (it == o.fit.parameters.end()) continue;  // not estimated (e.g. a damping the operator fixes)
      const ParameterEstimate& p = *it;
      if (!p.identifiable) {
        o.doubts.push_back(name + " is not identifiable from the data");
        continue;
      }
      if (p.std > thresholds::kPoorlyDetermined * std::abs(p.value))
        o.doubts.push_back(name + " is poorly determined (std over 50 % of its value)");
      const int index = info.parameter_index(name);
      if (index < 0) continue;
      const std::string side = pressed_bound(p, info.parameters[static_cast<std::size_t>(index)]);
      if (!side.empty()) o.doubts.push_back(name + " sits at its " + side + " bound");
    }
  }

  // A candidate that explains the data by a new body's resonance (Extension::resonating_bodies) must show one: a
  // mode of the new bodies that carries at least thresholds::kShownModeShare of a measured channel's response at its
  // frequency (new_body_modes.hpp). Otherwise the body is not evidenced by the data: a doubt.
  static void judge_new_body_modes(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s,
                                   CandidateOutcome& o) {
    if (ext.resonating_bodies.empty()) return;
    NewBodyMode mode;
    try {
      mode = best_seen_new_body_mode(evaluator, s.fit.values, ext.resonating_bodies, s.channels);
    } catch (const std::runtime_error&) {
      return;  // no modes at these values (an overflowing state matrix): the fit's own doubts stand
    }
    std::string bodies;
    for (const std::string& b : ext.resonating_bodies) bodies += (bodies.empty() ? "" : ", ") + b;
    const std::string none = "no resonance of " + bodies + " shows in the data: ";
    if (!mode.oscillating)
      o.doubts.push_back(none + "its modes are overdamped");
    else if (mode.channel.empty())
      o.doubts.push_back(none + format("its mode at %.4g Hz lies outside the measured band", mode.f_hz));
    else if (mode.share < thresholds::kShownModeShare)
      o.doubts.push_back(none + format("its mode at %.4g Hz, damped at %.0f %% of critical, carries %.2g %% of the "
                                       "response there",
                                       mode.f_hz, 100 * mode.zeta, 100 * mode.share) +
                         " (" + mode.channel + format("; a resonance carries at least %.0f %%)",
                                                      100 * thresholds::kShownModeShare));
  }

  const std::vector<DataSet>& data_;
  const DiagnoseOptions& options_;
  SplitData split_;
  bool has_records_;  // some data set is a time record
  mutable std::mutex fit_progress_mutex_;
  std::vector<double> prior_peaks_;
  std::set<std::string> sensor_outputs_;  // outputs the nominal model misses more than all others
  std::vector<DataSet> screen_data_;  // what candidates are screened on: FRFs, the records' H1 estimates for records
  int screen_averages_ = 1;           // the H1 estimates' segments (their coherence's weighting)
  bool screen_on_companion_ = false;  // screen_data_ are the records' H1 estimates
  std::map<std::string, std::vector<double>> prior_output_peaks_;
  std::vector<ChannelResidual> prior_channels_;  // measured against the current model at its prior values
  std::vector<ReversedDrivingPoint> reversed_;   // driving points whose data a passive structure cannot give
};

}  // namespace

const CandidateOutcome* selected_outcome(const DiagnosisResult& result, const std::string& id) {
  for (auto it = result.candidates.rbegin(); it != result.candidates.rend(); ++it)
    if (it->id == id && it->qualifies) return &*it;
  return nullptr;
}

DiagnosisResult diagnose(const ir::ModelIr& model, const std::string& model_text, const std::vector<DataSet>& data,
                         const DiagnoseOptions& options) {
  return Diagnoser(data, options).run(model, model_text);
}

}  // namespace mbgen::diagnosis
