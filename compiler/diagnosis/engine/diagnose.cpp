#include "diagnosis/engine/diagnose.hpp"

#include <algorithm>
#include <set>

#include <mbgen/estimation/spectral_companion.hpp>
#include <mbgen/methods/modal_start.hpp>

#include "diagnosis/engine/candidate_fits.hpp"
#include "diagnosis/engine/candidate_judging.hpp"
#include "diagnosis/engine/chain_selection.hpp"
#include "diagnosis/engine/driving_points.hpp"
#include "diagnosis/engine/judging.hpp"
#include "diagnosis/engine/model_fits.hpp"
#include "diagnosis/engine/model_text.hpp"
#include "diagnosis/engine/prior_peaks.hpp"
#include "diagnosis/engine/text_format.hpp"

namespace mbgen::diagnosis {

namespace {

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

// The rounds of the search: each fits the candidates on the current model (candidate_fits.hpp) and takes the best
// by the judging rules (judging.hpp).
class Diagnoser {
 public:
  Diagnoser(const std::vector<DataSet>& data, const DiagnoseOptions& options) : fits_(data, options) {}

  // The loop of the method (docs/diagnosis.md): fit and judge the nominal model, extend it greedily one candidate
  // per round while a candidate explains what is wrong, then keep the extension only if it explains enough.
  DiagnosisResult run(const ir::ModelIr& model, const std::string& text) {
    DiagnosisResult result;
    result.model_file = model.file;
    result.seed = fits_.options().fit.seed;
    for (const DataSet& d : fits_.data()) result.data.push_back(d.file());
    reversed_ = reversed_driving_points(model, fits_.data());
    result.nominal = assess_nominal(model, text);
    ModelState current = result.nominal;
    // The stopping rule: a model that shows no finding is adequate, and no candidate is fitted. The findings'
    // threshold holds the family-wise false-alarm rate over every window of lines judged at 0.05
    // (residual_analysis.hpp, finding_threshold), so a right model is extended, or called unexplained, at most that
    // often (docs/diagnosis.md, "The stopping rule").
    for (int round = 1; round <= fits_.options().max_extensions; ++round) {
      if (current.residual.discrepancies.empty()) {
        if (round == 1) fits_.say("nominal model: no finding beyond the noise; nothing to extend");
        break;
      }
      // A further round pursues what the nominal model gets wrong and the extensions taken have not explained, or,
      // while the extended model would not be kept (full_explanation), what it still shows: an effect the nominal
      // fit masked (a loose mount that shows only once an added mass is in). Once every nominal finding is explained
      // and the model would be kept, what the extended model alone shows is the form of its extensions (a base on
      // feet where the real base's feet stand elsewhere), which another extension would only tune: on such data a
      // joining spring from the housing to the floor "explained" the on-feet base's own misfit (delta BIC -1229).
      if (round > 1 && pending_findings(result, current).empty() &&
          full_explanation(result, current, fits_.options()).holds) {
        fits_.say(
            format("round %.0f: every finding of the nominal model is explained; the %.0f the extended model still "
                   "shows are the form of its extensions, not a further effect",
                   static_cast<double>(round), static_cast<double>(current.residual.discrepancies.size())));
        break;
      }
      if (!extend_once(round, result, current)) break;
    }
    drop_superseded(result, current);
    keep_only_full_explanations(result, current);
    if (!result.selected.empty())
      current.text = with_estimates(current.text, current.model.file, current.values, added_parameters(result));
    describe_at_final(result, current);
    result.final = current;
    result.verdict = verdict_of(result);
    fits_.say("verdict: " + result.verdict);
    return result;
  }

 private:
  // Fits and judges the nominal model; its findings steer the candidates (sensor outputs).
  ModelState assess_nominal(const ir::ModelIr& model, const std::string& text) {
    fits_.say("nominal model: fitting " + std::to_string(model.parameters.size()) + " parameters");
    // The caller's chosen starts (monitor: the baseline's levels), and the start from the data's modes before them.
    const std::unique_ptr<Model> evaluator = fits_.derive_model(model);
    FitOptions fo = fits_.options().fit;
    if (fits_.options().start_from_modes) {
      const ModalStart from_modes = start_from_modes(*evaluator, fits_.fit_data(), fits_.options().fit);
      fits_.say("nominal model: start from the data's modes: " + from_modes.summary);
      start_first_at(from_modes.values, fo);
    }
    ModelState nominal =
        fits_.assess(*evaluator, model, text, {}, fo.starts, Workers{fits_.options().fit.threads, nullptr, nullptr},
                     fo.also_start_at, {}, fo.further_starts_at);
    sensor_outputs_ = outputs_missed_alone(nominal.channels);
    fits_.say(format("nominal model: nrmse %.4g, validation %.4g, mean normalized residual %.3g", nominal.fit.nrmse,
                     nominal.validation_nrmse, nominal.residual.mean_z));
    for (const Discrepancy& d : nominal.residual.discrepancies) fits_.say("  finding: " + d.text);
    return nominal;
  }

  // With records, a round's candidates are screened on the records' H1 estimates, where a fit needs no simulation,
  // with the estimator's own bias at the current model's estimate divided out (spectral_companion.hpp): on the
  // plain H1 a spindle whose resonator was already in showed "evidence" for a compliant base (delta BIC -43) that
  // its fit on the records did not bear out, one full fit on the records per such candidate. Records too short for
  // H1 estimates are screened on themselves.
  void screen_on_records_h1(const Model& evaluator, const ModelState& current) {
    if (!fits_.has_records()) return;
    if (auto companion = estimation::debiased_spectral_companion(evaluator, current.fit.values, fits_.fit_data()))
      fits_.screen_on_h1(std::move(companion->data), companion->averages);
  }

  // One round of the greedy forward selection: every candidate on the current model, scored; the best qualifying one
  // is taken if it explains the discrepancy. Another round follows while the extended model still shows a finding:
  // two independent effects (a sensor's calibration and a loose mount) are named one per round, and a candidate that
  // did not qualify against the nominal model may against the extended one (the loose mount, once the calibration is
  // right). False when the search ends.
  bool extend_once(int round, DiagnosisResult& result, ModelState& current) {
    const std::unique_ptr<Model> evaluator = fits_.derive_model(current.model);
    prior_ = prior_peaks(*evaluator, fits_.data(), fits_.options().fit.frf_weighting);
    screen_on_records_h1(*evaluator, current);
    const ExtensionContext ctx = context(current);
    std::string hints;
    for (double f : ctx.peak_hz) hints += format(" %.1f", f);
    if (!hints.empty()) fits_.say("round " + std::to_string(round) + ": peaks to place new modes at (Hz):" + hints);
    std::vector<Extension> extensions = enumerate_extensions(current.model, current.text, ctx);
    // The measurement chain's candidates come first in the list; only those the data support are fitted.
    const auto structural = std::stable_partition(extensions.begin(), extensions.end(),
                                                  [](const Extension& e) { return e.operator_name == kChainOperator; });
    std::vector<Extension> chain(std::make_move_iterator(extensions.begin()), std::make_move_iterator(structural));
    chain = chain_candidates_worth_fitting(std::move(chain), current, prior_.channels, reversed_,
                                           [this](const std::string& line) { fits_.say(line); });
    extensions.erase(extensions.begin(), structural);
    extensions.insert(extensions.begin(), std::make_move_iterator(chain.begin()), std::make_move_iterator(chain.end()));
    if (extensions.empty()) return false;
    std::vector<CandidateOutcome> outcomes;
    std::vector<ModelState> states;
    score_all(fits_, extensions, current, round, outcomes, states);
    keep_best_variants(outcomes, states);
    result.candidates.insert(result.candidates.end(), outcomes.begin(), outcomes.end());
    const std::size_t first_of_round = result.candidates.size() - outcomes.size();
    const int best = best_after_refits(result, current, outcomes, states, first_of_round);
    if (best < 0) return false;
    const Judgement agreed = predicts_as_well(outcomes, best);
    if (!agreed.holds) {
      fits_.say(agreed.why);
      return false;
    }
    ModelState& chosen = states[static_cast<std::size_t>(best)];
    fit_on_to_convergence(chosen);
    const CandidateOutcome& winner = outcomes[static_cast<std::size_t>(best)];
    const Judgement explained =
        explains(current, chosen, fits_.options().max_extensions - round, fits_.options().max_final_residual,
                 winner.operator_name == "sensor_dynamics" ? winner.target : "");
    if (!explained.why.empty()) fits_.say(explained.why);
    if (!explained.holds) return false;
    result.selected.push_back(outcomes[static_cast<std::size_t>(best)].id);
    result.selected_variants.push_back(winner.variant);
    for (const Extension& e : extensions)  // the fitted candidates: the winner is among them
      if (e.id == winner.id && e.variant == winner.variant) taken_.push_back({e, ctx, round});
    result.explains.push_back(findings_cleared(result, current, chosen));
    for (const std::string& id : equivalents(outcomes, best))
      fits_.say("  " + id + " fits exactly as well: the same extension in another place");
    fits_.say("selected " + result.selected.back());
    declare_held_known(chosen);
    current = std::move(chosen);
    return !current.residual.discrepancies.empty();
  }

  // The candidate taken was fitted as far as ranking candidates needs (DiagnoseOptions::candidate_stall_gain). It is
  // fitted on from there to the full tolerance, its held parameters held, before it is judged and the next round
  // starts from it: the spindle's loose mount (outside the library, draw 6), taken in round 1, stood 10 above its
  // optimum in cost (about 30 in BIC) where its fit stalled, and the next round's fits would all start there.
  void fit_on_to_convergence(ModelState& s) const {
    if (!(fits_.candidate_stall_gain() > 0)) return;
    try {
      ModelState on = fits_.assess(*fits_.derive_model(s.model), s.model, s.text, s.values, 1,
                                   Workers{fits_.options().fit.threads, nullptr, nullptr}, {}, s.held);
      if (on.fit.cost < s.fit.cost) s = std::move(on);
    } catch (const std::exception&) {
      // not evaluable on from there: the candidate's fit stands
    }
  }

  // The best qualifying candidate of a round, once the current model's own fit has been checked against it. A
  // candidate may win only because its search found a better optimum of the parameters it shares with the
  // current model. Re-fit the current model from the winner's estimates: if that closes the gap, the gain was a
  // better fit, not an effect; the current model improves and the candidates are judged again against it.
  int best_after_refits(DiagnosisResult& result, ModelState& current, std::vector<CandidateOutcome>& outcomes,
                        const std::vector<ModelState>& states, std::size_t first_of_round) {
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
      return lowest >= 0 && outcomes[static_cast<std::size_t>(lowest)].delta_bic < fits_.options().min_delta_bic
                 ? lowest
                 : -1;
    };
    for (int guard = 0, from = source(); from >= 0 && guard < 3; ++guard, from = source()) {
      if (fits_.screen_on_companion() &&
          !fits_.leads_lower_on_companion(*fits_.derive_model(current.model), {},
                                          states[static_cast<std::size_t>(from)].values, current.values))
        break;
      // A start the current model cannot be evaluated at is no better optimum: the current fit stands. (An mdof2
      // support with a Maxwell element, draw 6: a compliant wall's fit took the delay on d2, selected the round
      // before, to 0 s, where the delay's coordinate has no mass, and the whole diagnosis stopped with an error.)
      ModelState refit;
      try {
        refit = fits_.assess(current.model, current.text, states[static_cast<std::size_t>(from)].values,
                             fits_.options().candidate_starts);
      } catch (const std::exception&) {
        break;
      }
      if (!(refit.fit.cost < current.fit.cost * (1.0 - 1e-9))) break;
      fits_.say("the current model fits better started from the estimate of " +
                outcomes[static_cast<std::size_t>(from)].id +
                format(" (cost %.6g -> %.6g", current.fit.cost, refit.fit.cost) +
                format(", BIC %.1f -> %.1f): a better optimum, not an effect; judging the candidates again",
                       current.fit.bic, refit.fit.bic));
      if (result.selected.empty()) result.nominal = refit;  // the current model is still the nominal one
      current = std::move(refit);
      for (std::size_t k = 0; k < outcomes.size(); ++k) {
        CandidateOutcome& o = outcomes[k];
        if (!o.error.empty() || !o.fully_fitted) continue;
        rank_against(current, fits_.options(), o);
        result.candidates[first_of_round + k] = o;
      }
      best = best_qualifying(outcomes);
    }
    return best;
  }

  // DiagnosisResult::described: each selected extension's description at the final model's fit.
  void describe_at_final(DiagnosisResult& result, const ModelState& final_state) const {
    result.described.clear();
    if (result.selected.empty()) return;
    const std::unique_ptr<Model> evaluator = fits_.derive_model(final_state.model);
    for (std::size_t i = 0; i < result.selected.size(); ++i) {
      const CandidateOutcome* o = selected_outcome(result, result.selected[i]);
      std::string text = o ? o->description : "";
      for (const Taken& t : taken_)
        if (t.extension.id == result.selected[i] && t.extension.variant == result.selected_variants[i])
          text = described_at(t.extension, *evaluator, final_state, text);
      result.described.push_back(std::move(text));
    }
  }

  // Backward elimination of the first of two extensions taken (docs/diagnosis.md, step 7). Greedy rounds take the
  // largest gain first, and the second extension may do the first one's work better: a low-pass on d2 taken for
  // what was a delay's phase lag, and then the delay itself. The second is applied to the nominal model alone and
  // fitted from the final estimates; when the final model's BIC is lower than that by less than a round's least
  // evidence (|min_delta_bic|) and the second alone qualifies against the nominal model, the first is superseded:
  // dropped, and the model without it is the current one.
  void drop_superseded(DiagnosisResult& result, ModelState& current) {
    if (result.selected.size() != 2 || taken_.size() != 2) return;
    const Taken& first = taken_[0];
    const Taken& second = taken_[1];
    const Extension* alone = nullptr;
    const std::vector<Extension> on_nominal =
        enumerate_extensions(result.nominal.model, result.nominal.text, second.context);
    for (const Extension& e : on_nominal)
      if (e.id == second.extension.id && e.variant == second.extension.variant &&
          e.new_parameters.size() == second.extension.new_parameters.size())
        alone = &e;
    if (!alone) return;
    // Start at the final estimates; the second's new parameters (renamed where the first's took their names) at its
    // estimates, and held where the final model holds them.
    std::map<std::string, double> start = current.values;
    std::vector<std::string> held;
    for (std::size_t k = 0; k < alone->new_parameters.size(); ++k) {
      const std::string& was = second.extension.new_parameters[k].name;
      const std::string& now = alone->new_parameters[k].name;
      const auto value = current.values.find(was);
      if (value == current.values.end()) return;
      start[now] = value->second;
      for (const ir::Parameter& p : current.model.parameters)
        if (p.name == was && p.role == ir::Role::Known) held.push_back(now);
    }
    const std::unique_ptr<Model> evaluator = fits_.derive_model(alone->model);
    ModelState without;
    try {
      without = fits_.assess(*evaluator, alone->model, alone->mdl_text, start, 1,
                             Workers{fits_.options().fit.threads, nullptr, nullptr}, {}, held);
    } catch (const std::exception&) {
      return;  // not evaluable there: the two stand
    }
    CandidateOutcome outcome = judge(*alone, *evaluator, without, result.nominal, second.round, fits_.options());
    outcome.description += " (fitted again without " + label(first.extension) + ")";
    const double rise = without.fit.bic - current.fit.bic;
    if (!outcome.qualifies || !(rise < -fits_.options().min_delta_bic)) {
      fits_.say(label(first.extension) + format(" stays: without it the BIC goes from %.1f to %.1f", current.fit.bic,
                                                without.fit.bic));
      return;
    }
    fits_.say(label(first.extension) + " is superseded by " + label(second.extension) +
              format(": without it the BIC goes from %.1f to %.1f (a round needs a fall of %.0f); dropped",
                     current.fit.bic, without.fit.bic, -fits_.options().min_delta_bic));
    result.superseded.push_back({first.extension.id, first.extension.variant, first.round, rise});
    result.selected = {second.extension.id};
    result.selected_variants = {second.extension.variant};
    result.explains = {findings_cleared(result, result.nominal, without)};
    result.candidates.push_back(std::move(outcome));
    declare_held_known(without);
    current = std::move(without);
    taken_.erase(taken_.begin());
  }

  // The selected extensions are kept only if together they explain enough (full_explanation); otherwise nothing is
  // selected, the reasons are said with the nominal findings that still show, and the current model is the nominal
  // one again.
  void keep_only_full_explanations(DiagnosisResult& result, ModelState& current) const {
    if (result.selected.empty()) return;
    const Judgement kept = full_explanation(result, current, fits_.options());
    if (kept.holds) return;
    fits_.say(kept.why);
    for (const Discrepancy* d : kept.still)
      fits_.say("  still: " + d->text +
                format(" (band residual %.3g -> %.3g)", band_mean_z(result.nominal.channels, *d),
                       band_mean_z(current.channels, *d)));
    result.selected.clear();
    result.selected_variants.clear();
    result.explains.clear();
    current = result.nominal;
  }

  // Peaks for new parameters' start values: first the data's peaks that the prior model does not account for
  // (strongest first: the most direct evidence of a missing mode), then the fitted model's unexplained resonances.
  ExtensionContext context(const ModelState& s) const {
    ExtensionContext ctx;
    for (double f : prior_.peak_hz) add_distinct(ctx.peak_hz, f);
    ctx.output_peak_hz = prior_.output_peak_hz;
    for (const Discrepancy& d : s.residual.discrepancies)  // already strongest first
      if (d.kind == "unexplained_resonance") {
        add_distinct(ctx.peak_hz, d.f_hz);
        add_distinct(ctx.output_peak_hz[output_of(d.channel)], d.f_hz);
      }
    ctx.varying_parameters = varying_parameters(fits_.data());
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
    // A phase drift that one output alone shows is a signal chain's signature as well (a low-pass's lag, a delay),
    // also where the structure's misfit shows on every output: a compliant base beside a low-pass on xs_front.
    std::set<std::string> drifting;
    for (const Discrepancy& d : s.residual.discrepancies) {
      if (d.kind != "phase_trend") continue;
      drifting.insert(output_of(d.channel));
      if (!ctx.output_delay_s.count(output_of(d.channel))) ctx.output_delay_s[output_of(d.channel)] = d.delay_s;
    }
    if (drifting.size() == 1) ctx.outputs_with_findings.insert(*drifting.begin());
    for (const ChannelResidual& c : s.channels) {
      if (c.f_hz.empty()) continue;
      ctx.band_lo_hz = ctx.band_lo_hz > 0 ? std::min(ctx.band_lo_hz, c.f_hz.front()) : c.f_hz.front();
      ctx.band_hi_hz = std::max(ctx.band_hi_hz, c.f_hz.back());
    }
    return ctx;
  }

  // A selected extension as it was enumerated, and the context of its round: to apply it to another model.
  struct Taken {
    Extension extension;
    ExtensionContext context;
    int round = 0;
  };

  FitContext fits_;
  std::vector<Taken> taken_;                    // the selected extensions, in the order taken
  PriorPeaks prior_;                            // the data's peaks against the current model at its priors
  std::set<std::string> sensor_outputs_;        // outputs the nominal model misses more than all others
  std::vector<ReversedDrivingPoint> reversed_;  // driving points whose data a passive structure cannot give
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
