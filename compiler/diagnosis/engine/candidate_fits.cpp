#include "diagnosis/engine/candidate_fits.hpp"

#include <algorithm>
#include <optional>
#include <set>

#include <mbgen/residuals/same_response.hpp>

#include "diagnosis/engine/candidate_judging.hpp"
#include "diagnosis/engine/screening.hpp"
#include "diagnosis/engine/text_format.hpp"
#include "diagnosis/engine/thresholds.hpp"

namespace mbgen::diagnosis {

namespace {

// A candidate's fit: two searches, around the current estimate and around the priors (where the current
// estimate has bent parameters to mimic the missing effect, the priors are the better start); the lower cost
// wins. Around the current estimate, the model's own parameters first settle around a new structural element
// (settling_held, FitOptions::settle_first).
// With time records one search starts from both (also_start_at): each search ends in simulation-based
// refinements of its best start and of its centre, which cost most of a candidate's time, so the priors get a
// start of the search rather than a search of their own.
// Each search also starts from the candidate's alternative starts (its new mode at the next peaks).
ModelState search(const FitContext& fits, const Extension& ext, const Model& evaluator, const ModelState& base,
                  const Workers& workers) {
  const std::vector<std::map<std::string, double>>& further = ext.alternative_starts;
  const std::vector<std::string> settle = settling_held(ext);
  if (fits.has_records()) {
    std::map<std::string, double> priors;
    for (const ParameterInfo& p : evaluator.info().parameters) priors[p.name] = p.value;
    return fits.assess(evaluator, ext.model, ext.mdl_text, base.values, fits.options().candidate_starts + 1, workers,
                       priors, {}, further, ext.nesting, settle);
  }
  ModelState s = fits.assess(evaluator, ext.model, ext.mdl_text, base.values, fits.options().candidate_starts,
                             workers, {}, {}, further, ext.nesting, settle);
  ModelState from_priors =
      fits.assess(evaluator, ext.model, ext.mdl_text, {}, fits.options().candidate_starts, workers, {}, {}, further);
  return from_priors.fit.cost < s.fit.cost ? std::move(from_priors) : std::move(s);
}

// A reduced fit: `held` (new parameters the data could not determine) back at their start values, the rest fitted
// from where the last fit ended, one local fit. What the data cannot determine leaves the cost nearly flat, so the
// optimum of the rest lies next to the last one (a new search from the centres took the spindle's base on feet 4 of
// its 7 s in a round of three reductions, and ended 1200-2700 higher in BIC).
ModelState reduced_fit(const FitContext& fits, const Extension& ext, const Model& evaluator, const ModelState& last,
                       const Workers& workers, const std::vector<std::string>& held) {
  std::map<std::string, double> start = last.values;
  for (const std::string& name : held) start.erase(name);  // at its prior, the start value of every search
  return fits.assess(evaluator, ext.model, ext.mdl_text, start, 1, workers, {}, held);
}

CandidateOutcome score(const FitContext& fits, const Extension& ext, const Model& evaluator, const ModelState& base,
                       int round, const Workers& workers, ModelState& state) {
  try {
    state = search(fits, ext, evaluator, base, workers);
    // New parameters the data cannot determine are held at their start values and the rest fitted again: on a
    // base on feet whose rocking about one axis the x-direction data barely see, that rocking's inertia ran to a
    // bound and took the base's depth and two foot constants with it ("not identifiable"), though the fit was
    // at the noise level. Holding some may leave others undetermined (what they were determined through): at
    // most three reductions (reduced_fit); what is left undetermined then is judged as it is.
    // Holding must not cost the candidate its evidence: a reduced fit no longer below the current model's BIC by
    // |min_delta_bic|, where the last fit was, shows that the data do determine what was held, only not sharply,
    // and the last fit stands. (A connection's damper on frame3, near zero with a wide spread, held at its start
    // value: delta BIC -859 became +36 000. Holding a base's rocking on feet costs some BIC and keeps the evidence.)
    std::vector<std::string> held;
    for (int reduction = 0; reduction < 3; ++reduction) {
      const std::vector<std::string> more = undetermined_new_parameters(ext, state.fit);
      if (more.empty() || held.size() + more.size() >= ext.new_parameters.size()) break;
      std::vector<std::string> holding = held;
      holding.insert(holding.end(), more.begin(), more.end());
      try {
        ModelState reduced = reduced_fit(fits, ext, evaluator, state, workers, holding);
        const double min_delta = fits.options().min_delta_bic;
        if (state.fit.bic - base.fit.bic < min_delta && !(reduced.fit.bic - base.fit.bic < min_delta)) break;
        state = std::move(reduced);
        held = std::move(holding);
      } catch (const std::exception&) {
        break;  // the reduced model could not be fitted or judged: the last fit stands
      }
    }
    return judge(ext, evaluator, state, base, round, fits.options());
  } catch (const std::exception& e) {
    return failed(ext, round, e.what());
  }
}

// Extension::start_from_variant: candidate k and the sibling variant it names both fully fitted; k is searched
// once more around where the sibling ended (two starts; with records searched on their H1 estimates and refined
// on the records, as every search; the parameters it holds held as before), and takes that fit if its cost is
// lower. True when it did.
bool refit_from_sibling(const FitContext& fits, const std::vector<Extension>& extensions,
                        const std::vector<std::unique_ptr<Model>>& evaluators,
                        const std::vector<std::shared_ptr<estimation::LocalFitMemo>>& memos, const ModelState& base,
                        int round, std::size_t k, std::vector<CandidateOutcome>& outcomes,
                        std::vector<ModelState>& states) {
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
  // With records, judged first on their H1 estimates (FitContext::leads_lower_on_companion's rule): refitted from
  // there, the variant must end lower than from its own estimate. And only the variant with the lowest BIC stands
  // for the candidate (keep_best_variants): where it stays above a plausible sibling, the refit on the records could
  // not change which variant that is, and it is not run. (The spindle's base in a 6 s record: the base on feet, its
  // rocking held, refitted for 10 s of 80 to end 69 000 above the simple base in BIC.)
  if (const std::optional<double> refitted = fits.bic_on_companion(*evaluators[k], states[k].held, start)) {
    const std::optional<double> own = fits.bic_on_companion(*evaluators[k], states[k].held, states[k].values);
    if (own && !(*refitted < *own + fits.options().min_delta_bic)) return false;
    if (outcomes[j].plausible) {
      const std::optional<double> sibling = fits.bic_on_companion(*evaluators[j], states[j].held, states[j].values);
      if (sibling && *refitted > *sibling + thresholds::kBicTie) return false;
    }
  }
  ModelState state;
  try {
    state = fits.assess(*evaluators[k], ext.model, ext.mdl_text, start, 2,
                        Workers{fits.options().fit.threads, nullptr, memos[k], fits.candidate_stall_gain()}, {},
                        states[k].held);
  } catch (const std::exception&) {
    return false;  // not fitted from there: the candidate's own fit stands
  }
  if (!(state.fit.cost < states[k].fit.cost)) return false;
  CandidateOutcome o = judge(ext, *evaluators[k], state, base, round, fits.options());
  o.screen_delta_bic = outcomes[k].screen_delta_bic;
  o.screen_records_delta_bic = outcomes[k].screen_records_delta_bic;
  fits.say(label(ext) + ": started from the " + from.variant + " variant's estimate it fits better: " + fitted_text(o));
  outcomes[k] = std::move(o);
  states[k] = std::move(state);
  return true;
}

}  // namespace

void score_all(const FitContext& fits, const std::vector<Extension>& extensions, const ModelState& base, int round,
               std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states) {
  const std::size_t n = extensions.size();
  std::vector<std::unique_ptr<Model>> evaluators(n);
  std::vector<std::string> derive_errors(n);
  std::vector<int> twin(n, -1);  // an earlier candidate that is the same model
  std::set<std::string> names_in_use;
  for (const auto& entry : base.values) names_in_use.insert(entry.first);
  for (const auto& entry : fits.options().set) names_in_use.insert(entry.first);
  for (const DataSet& d : fits.data())
    for (const auto& entry : d.set()) names_in_use.insert(entry.first);
  const std::vector<double> probes = probe_frequencies(fits.data());
  std::vector<std::shared_ptr<estimation::LocalFitMemo>> memos(n);
  const auto derive = [&](std::size_t k) {
    try {
      evaluators[k] = fits.derive_model(extensions[k].model);
    } catch (const std::exception& e) {
      derive_errors[k] = e.what();
      return;
    }
    for (std::size_t j = 0; j < k && twin[k] < 0; ++j)
      if (evaluators[j] && twin[j] < 0 && same_response(*evaluators[j], *evaluators[k], probes, names_in_use))
        twin[k] = static_cast<int>(j);
    if (twin[k] < 0) memos[k] = make_local_fit_memo();
  };
  // A round screens its first candidates while the later ones are still being derived (46 spindle candidates,
  // 0.6-1.6 s on one core; screening.hpp), if it screens at all: at most every candidate is fitted in its own right.
  // Not with time records: there the work of the full fits that follow depends on when the screening's starts ran
  // (what their memo holds; a race of refinements on the records, refinement_race.hpp, ends on the other thread's
  // pace), and the spindle's connection from a 1 s record, screened along with the derivations, took 76-113 s
  // against 47-65 s screened after them (the base on feet's full fit on the record), with the same results.
  const auto screening_cores = std::make_shared<ThreadBudget>(fits.options().fit.threads);
  std::optional<Screening> screening;
  std::vector<ScreeningFit> screened(n);
  // The candidates fitted in their own right: derived, and not the same model as an earlier one.
  const auto own_right = [&](std::size_t k) { return evaluators[k] && twin[k] < 0; };
  const auto screen = [&](std::size_t k) {
    if (own_right(k)) screened[k] = screening->fit(extensions[k], *evaluators[k], memos[k]);
  };
  const bool along = !fits.has_records() && Screening::applies(fits, n);
  if (along) {
    screening.emplace(fits, base, screening_cores);
    consume_while_producing(n, *screening_cores, derive, [&] { screening->fit_base(); }, screen);
  } else {
    for (std::size_t k = 0; k < n; ++k) derive(k);
  }
  std::vector<std::size_t> fitted;
  for (std::size_t k = 0; k < n; ++k)
    if (own_right(k)) fitted.push_back(k);
  // Otherwise screened after the derivations, where more are fitted in their own right than full fits have places
  // (known only now: twins are found as the models are derived).
  if (!along && Screening::applies(fits, fitted.size())) {
    screening.emplace(fits, base, screening_cores);
    screening->fit_base();
    ordered_parallel(n, *screening_cores, screen, [](std::size_t) {});
  }
  std::vector<char> screened_out(n, 0);
  outcomes.assign(n, CandidateOutcome{});
  states.assign(n, ModelState{});
  // Screened only where more were fitted in their own right than full fits have places; otherwise the screening
  // fits, made while the twins were not yet known, are not used.
  if (screening && Screening::applies(fits, fitted.size()))
    screening->select(extensions, fitted, round, screened, outcomes, states, screened_out);
  fitted.erase(std::remove_if(fitted.begin(), fitted.end(), [&](std::size_t k) { return screened_out[k] != 0; }),
               fitted.end());
  // Candidates side by side (each fit on one thread) keep the cores busy through a fit's serial stretches; a core
  // that finds no candidate left joins the starts of the fits still running.
  const Workers workers{1, std::make_shared<ThreadBudget>(fits.options().fit.threads), nullptr};
  std::size_t said = 0;
  const auto say_done_up_to = [&](std::size_t end) {
    for (; said < end; ++said) {
      const Extension& ext = extensions[said];
      const CandidateOutcome& o = outcomes[said];
      const std::string as = twin[said] < 0 ? "" : "  (the same model as " + label(extensions[twin[said]]) + ")";
      const std::string result =
          !o.error.empty() ? "failed: " + o.error
          : !o.fully_fitted
              ? format("screened out (screening delta BIC %.1f", o.screen_delta_bic) +
                    (fits.has_records() ? format(", on the records %.1f)", o.screen_records_delta_bic) : ")")
              : fitted_text(o);
      fits.say(format("[%.0f/%.0f] ", static_cast<double>(said + 1), static_cast<double>(n)) + label(ext) + ": " +
               result + as);
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
        outcomes[k] = judge(extensions[k], *evaluators[k], states[k], base, round, fits.options());
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
            score(fits, extensions[k], *evaluators[k], base, round,
                  Workers{1, workers.cores, memos[k], fits.candidate_stall_gain()}, states[k]);
        outcomes[k].screen_delta_bic = screened;
        outcomes[k].screen_records_delta_bic = on_records;
      },
      [&](std::size_t i) {
        const std::size_t end = i + 1 < fitted.size() ? fitted[i + 1] : n;
        for (std::size_t k = fitted[i] + 1; k < end; ++k) settle(k);
        say_done_up_to(end);
      });
  for (std::size_t k : fitted)
    if (refit_from_sibling(fits, extensions, evaluators, memos, base, round, k, outcomes, states))
      for (std::size_t t = k + 1; t < n; ++t)
        if (twin[t] == static_cast<int>(k)) settle(t);
}

}  // namespace mbgen::diagnosis
