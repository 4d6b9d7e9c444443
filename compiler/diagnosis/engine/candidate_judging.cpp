#include "diagnosis/engine/candidate_judging.hpp"

#include <algorithm>
#include <cmath>

#include <mbgen/dynamics/frf.hpp>

#include "diagnosis/engine/new_body_modes.hpp"
#include "diagnosis/engine/text_format.hpp"
#include "diagnosis/engine/thresholds.hpp"

namespace mbgen::diagnosis {

namespace {

// Why a fully fitted candidate is not plausible, for its progress line.
std::string doubts_text(const CandidateOutcome& o) {
  if (o.plausible || o.doubts.empty()) return {};
  std::string out = "  (implausible: ";
  for (std::size_t i = 0; i < o.doubts.size(); ++i) out += (i ? "; " : "") + o.doubts[i];
  return out + ")";
}

// New (and freed) parameters must be determined by the data and physically sensible: identifiable, known to
// better than 50 %, and not pressed against a bound (the optimum would lie beyond what is physical).
void judge_plausibility(const Extension& ext, const ModelInfo& info, CandidateOutcome& o) {
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
void judge_new_body_modes(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s,
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
    o.doubts.push_back(none +
                       format("its mode at %.4g Hz, damped at %.0f %% of critical, carries %.2g %% of the "
                              "response there",
                              mode.f_hz, 100 * mode.zeta, 100 * mode.share) +
                       " (" + mode.channel +
                       format("; a resonance carries at least %.0f %%)", 100 * thresholds::kShownModeShare));
}

// Whether the data cannot tell parameter `name`'s size from the structure's scale: doubling every other estimated
// parameter and doubling or halving this one leaves every FRF of the model as it is (a force's factor where every
// mass, stiffness and damping is estimated, or the factor of a model's only output). Checked on the model's FRFs at
// a few of the data's lines; a fit then holds some parameter or stops at a bound, and the factor's size and std it
// reports are only relative to that.
bool scale_confounded(const mbgen::Model& evaluator, const ModelState& s, const std::string& name) {
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

}  // namespace

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

std::string label(const Extension& ext) { return ext.id + (ext.variant.empty() ? "" : " (" + ext.variant + ")"); }

CandidateOutcome outline(const Extension& ext, int round) {
  CandidateOutcome o;
  o.id = ext.id;
  o.operator_name = ext.operator_name;
  o.target = ext.target;
  o.description = ext.description;
  o.variant = ext.variant;
  o.round = round;
  o.new_parameters = ext.new_parameters;
  o.freed_parameters = ext.freed_parameters;
  return o;
}

CandidateOutcome failed(const Extension& ext, int round, const std::string& error) {
  CandidateOutcome o = outline(ext, round);
  o.error = error;
  return o;
}

std::string fitted_text(const CandidateOutcome& o) {
  return format("delta BIC %.1f, validation %.4g", o.delta_bic, o.validation_nrmse) +
         (o.qualifies ? "  (qualifies)" : "") + doubts_text(o);
}

std::vector<std::string> undetermined_new_parameters(const Extension& ext, const FitResult& fit) {
  std::vector<std::string> out;
  for (const NewParameter& np : ext.new_parameters)
    for (const ParameterEstimate& p : fit.parameters)
      if (p.name == np.name && p.pull_chi2 <= thresholds::kBoundPullChi2 &&
          (!p.identifiable || p.std > thresholds::kPoorlyDetermined * std::abs(p.value)))
        out.push_back(p.name);
  return out;
}

std::string chain_description(const Extension& ext, const FitResult& fit, const std::string& otherwise,
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
      return (input ? "the recorded " + what +
                          " has the opposite sign of the force applied (a reaction force taken "
                          "with the wrong sign)"
                    : what + " reads with the opposite sign: the sensor is mounted or wired reversed") +
             size;
    return (input ? "the recorded " + what + " is a constant factor of the force applied"
                  : what +
                        " reads a constant "
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
  static const Unit kUnits[] = {{1e3, "millimetres read as metres"},
                                {1e-3, "metres read as millimetres"},
                                {1 / 9.80665, "m/s^2 read as g"},
                                {9.80665, "g read as m/s^2"}};
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

std::string described_at(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s,
                         const std::string& otherwise) {
  if (ext.operator_name != kChainOperator) return otherwise;
  return chain_description(ext, s.fit, otherwise,
                           ext.new_parameters.size() == 1 && scale_confounded(evaluator, s, ext.new_parameters[0].name));
}

void rank_against(const ModelState& base, const DiagnoseOptions& options, CandidateOutcome& o) {
  o.delta_bic = o.fit.bic - base.fit.bic;
  o.qualifies = o.plausible && o.delta_bic < options.min_delta_bic &&
                o.validation_nrmse < (1.0 - options.min_validation_gain) * base.validation_nrmse;
}

CandidateOutcome judge(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s, const ModelState& base,
                       int round, const DiagnoseOptions& options) {
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
  o.description = described_at(ext, evaluator, s, o.description);
  judge_plausibility(ext, s.info, o);
  judge_new_body_modes(ext, evaluator, s, o);
  o.plausible = o.doubts.empty();
  rank_against(base, options, o);
  return o;
}

void keep_best_variants(std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states) {
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

std::vector<std::string> equivalents(const std::vector<CandidateOutcome>& outcomes, int best) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < outcomes.size(); ++k)
    if (static_cast<int>(k) != best && outcomes[k].qualifies &&
        std::abs(outcomes[k].delta_bic - outcomes[static_cast<std::size_t>(best)].delta_bic) <= thresholds::kBicTie)
      out.push_back(outcomes[k].id);
  return out;
}

}  // namespace mbgen::diagnosis
