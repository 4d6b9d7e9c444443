// Candidate extensions of a model for `mbgen diagnose` (ids: docs/interfaces.md, operators:
// docs/extensions.md).
//
// Each operator looks at the model's own structure (its grounds, bodies, elements, parameters and signals) and
// proposes small changes, each with few new parameters so that the data can identify them. The diagnosis fits
// every candidate and keeps those the data justify.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

struct NewParameter {
  std::string name;
  std::string why;  // what the parameter stands for, one short phrase
};                  // its start value and bounds are in the extended model's parameter of that name

struct Extension {
  std::string id;             // "<operator>:<target>", e.g. "compliant_ground:base"
  std::string operator_name;  // "compliant_ground"
  std::string target;         // "base" (for connection: "A-B")
  // Variants: an operator may offer several versions of one candidate under one id (untie_parameter: which
  // element differs). They are consecutive in the list, each named here; the diagnosis fits them all and keeps
  // the best. Empty for a candidate without variants.
  std::string variant;
  std::string description;    // one plain sentence a test engineer understands
  ir::ModelIr model;            // the extended model; new parameters have role estimate and a start value
  std::vector<NewParameter> new_parameters;
  std::vector<std::string> freed_parameters;  // existing parameters whose role becomes estimate
  std::string mdl_text;  // the extended model as .mdl: the original text with a small, commented change
  // Other start values of the new parameters (by name), worth a start of the fit each: those the operator gives
  // when it places the new mode at the context's second, third... peak instead of the strongest (the strongest
  // peak may be one the fit accounts for by moving a mode; the one the model misses comes later). Empty for a
  // candidate whose start does not depend on the peaks.
  std::vector<std::map<std::string, double>> alternative_starts;
  // A start from a sibling variant's estimate (empty `variant`: none). A richer variant that nearly contains a
  // simpler sibling may miss its optimum where the sibling finds one: when both are fully fitted, it is searched
  // again from where the sibling ended (the sibling's values of the parameters both have, and each new parameter
  // named in `from` at factor times the sibling's parameter named there) and keeps the better fit.
  struct VariantStart {
    std::string variant;
    std::map<std::string, std::pair<std::string, double>> from;  // new parameter -> (sibling's parameter, factor)
  };
  VariantStart start_from_variant;
  // Values of new parameters at which the extended model is the current one again (an untied copy at the shared
  // parameter's value, a joining spring at zero stiffness), where such a point exists and is not already the
  // start; empty otherwise (a compliant ground or a resonator reaches the current model only in a limit). The
  // fits around the current estimate also start there: at the current model's own optimum, from which a fit can
  // only improve on it (docs/diagnosis.md, "Screening"). Starts elsewhere alone, near the noise level a fit
  // could end far above the current model and the candidate be screened out for that.
  std::map<std::string, double> nesting;
  // New bodies whose own resonance the candidate puts forward as the explanation (a compliant ground's base, a
  // resonator's mass): the data must show one of their modes (docs/diagnosis.md, step 6). Empty for candidates
  // that claim no resonance of their own (a sensor's mounting may resonate far above the band).
  std::vector<std::string> resonating_bodies;
};

// What a fit of e around the current estimate holds at their start values while the model's own parameters settle
// around them first (FitOptions::settle_first): the new parameters of an element of the structure (a body, spring,
// mass or mode), which the current estimate, fitted without it, has partly absorbed. None for the measurement
// chain's factors and a sensor's dynamics: they leave the structure's modes where they are, and the chain's
// factors start at their least-squares values against the current estimate already (settled the other way round;
// the structure settled around a held input factor took it as a scale, spindle mount and mass, draw 2).
inline std::vector<std::string> settling_held(const Extension& e) {
  std::vector<std::string> names;
  if (e.operator_name == "measurement_chain" || e.operator_name == "sensor_dynamics") return names;
  for (const NewParameter& p : e.new_parameters) names.push_back(p.name);
  return names;
}

struct ExtensionContext {
  std::vector<double> peak_hz;               // unexplained resonances in the residual, strongest first (may be empty)
  // The same per output (the channels "OUTPUT/INPUT" of that output), strongest first; outputs without one absent.
  std::map<std::string, std::vector<double>> output_peak_hz;
  std::set<std::string> varying_parameters;  // parameters the data sets set differently (e.g. n_sp)
  // Outputs whose misfit a sensor's signal conditioning could explain (its filters): one the model misses alone
  // (more than twice every other output, from the nominal model on), or the one output whose phase drifts.
  std::set<std::string> outputs_with_findings;
  std::map<std::string, double> output_delay_s;  // a delay the residual's phase shows on the output's channels
  double band_lo_hz = 0, band_hi_hz = 0;         // the judged lines' frequency range over all data
  std::map<std::string, double> values;      // current (fitted) values of the nominal model's free parameters
};

// Peaks beyond the strongest that give a candidate an alternative start (Extension::alternative_starts).
inline constexpr std::size_t kAlternativePeaks = 2;

// All candidates, in a fixed order: by operator (measurement_chain, compliant_ground, gyroscopic, free_parameter,
// untie_parameter, moment_stiffness, added_mass, resonator, sensor_dynamics, connection), then in the model's
// declaration order.
// Ids are unique, except that the variants of one candidate (distinct `variant`s) share its id.
// `nominal_text` is the text `nominal` was parsed from; each candidate's mdl_text parses to its model.
std::vector<Extension> enumerate_extensions(const ir::ModelIr& nominal, const std::string& nominal_text,
                                            const ExtensionContext& ctx);

}  // namespace mbgen::diagnosis
