// The table of estimation methods (mbgen/methods/method_table.hpp): one descriptor per method, in --method's order.
// The help texts and preconditions say what docs/methods.md says at more length.
#include "mbgen/methods/method_table.hpp"

#include "mbgen/methods/arx_two_stage.hpp"
#include "mbgen/methods/direct.hpp"
#include "mbgen/methods/eiv.hpp"
#include "mbgen/methods/hybrid.hpp"
#include "mbgen/methods/modal_fit.hpp"

#include <algorithm>

namespace mbgen {

namespace {

FitResult run_output_error(const MethodRun& r) { return fit(r.model, r.data, r.fit); }
FitResult run_direct(const MethodRun& r) { return fit_direct(r.model, r.data, r.fit); }
FitResult run_hybrid(const MethodRun& r) { return fit_hybrid(r.model, r.data, r.fit); }
FitResult run_ekf(const MethodRun& r) { return fit_ekf(r.model, r.data, r.fit, r.options.ekf); }
FitResult run_arx_two_stage(const MethodRun& r) { return fit_arx_two_stage(r.model, r.data, r.fit); }
FitResult run_modal(const MethodRun& r) { return fit_modal(r.model, r.data, r.fit); }
FitResult run_eiv(const MethodRun& r) { return fit_eiv(r.model, r.data, r.fit); }

// --two-step-route names the numerical route "numerical"; TwoStepOptions::solver calls it "newton". The exact
// solver is derived only where the route may take it.
FitResult run_two_step(const MethodRun& r) {
  TwoStepOptions o = r.options.two_step;
  const std::string& route = r.options.two_step_route;
  o.solver = route == "numerical" ? "newton" : route;
  if ((route == "auto" || route == "analytical") && r.options.analytical_solver) o.analytical = r.options.analytical_solver();
  return fit_two_step(r.model, r.data, r.fit, o);
}

MethodOption choice(std::string flag, std::string help, std::vector<std::string> choices,
                    std::string& (*text)(MethodOptions&)) {
  MethodOption o;
  o.flag = std::move(flag);
  o.help = std::move(help);
  o.kind = MethodOption::Kind::Choice;
  o.choices = std::move(choices);
  o.text = text;
  return o;
}

MethodOption non_negative(std::string flag, std::string help, double& (*number)(MethodOptions&)) {
  MethodOption o;
  o.flag = std::move(flag);
  o.help = std::move(help);
  o.kind = MethodOption::Kind::NonNegativeNumber;
  o.number = number;
  return o;
}

std::vector<MethodOption> two_step_options() {
  return {
      choice("--two-step-route",
             "two-step: step two's route: auto (analytical where the coefficient equations have a closed form, else "
             "numerical where square, else minimisation), analytical, numerical or minimisation",
             {"auto", "analytical", "numerical", "minimisation"},
             [](MethodOptions& o) -> std::string& { return o.two_step_route; }),
      choice("--two-step-model",
             "two-step from records: step one's model, armax (default: the prediction-error method) or arx (least "
             "squares)",
             {"armax", "arx"}, [](MethodOptions& o) -> std::string& { return o.two_step.model; }),
      choice("--two-step-criterion", "two-step from records: the order criterion, aic (default), bic or fpe",
             {"aic", "bic", "fpe"}, [](MethodOptions& o) -> std::string& { return o.two_step.criterion; }),
      choice("--two-step-weighting",
             "two-step: step two's residuals, normalised (default: the thesis's) or covariance (whitened by step "
             "one's coefficient covariance)",
             {"normalised", "covariance"}, [](MethodOptions& o) -> std::string& { return o.two_step.weighting; }),
  };
}

std::vector<MethodOption> ekf_options() {
  return {non_negative("--ekf-drift",
                       "ekf: each parameter's random walk, its relative std over the whole data (default 0.05; 0: "
                       "constant parameters)",
                       [](MethodOptions& o) -> double& { return o.ekf.drift; })};
}

MethodDescriptor output_error(std::string name, std::string help, bool frf, bool records, std::string needs) {
  MethodDescriptor m;
  m.name = std::move(name);
  m.help = std::move(help);
  m.takes_frf = frf;
  m.takes_records = records;
  m.needs = std::move(needs);
  m.output_error = true;
  m.run = run_output_error;
  return m;
}

// The direct method's sensors, which hybrid needs too (it starts from the direct estimate).
std::vector<MethodPrecondition> direct_preconditions() {
  return {{"the motion of every coordinate the measured inputs move (outputs that give each coordinate)",
           "needs the motion of every coordinate", {"auto", "two-step"}},
          {"an output map that does not depend on an estimated parameter", "needs an output map that does not depend",
           {"auto", "two-step"}},
          {"outputs of one kind in a time record (all displacements, velocities or accelerations)",
           "on time records needs outputs of one kind", {"auto", "two-step"}}};
}

std::vector<MethodDescriptor> make_table() {
  std::vector<MethodDescriptor> t;
  t.push_back(output_error("auto", "by the data", true, true, ""));
  t.push_back(output_error("frf-output-error", "", true, false, "FRF data"));
  t.push_back(output_error("time-output-error", "", false, true, "time records"));

  MethodDescriptor direct;
  direct.name = "direct";
  direct.takes_frf = direct.takes_records = true;
  direct.preconditions = direct_preconditions();
  direct.run = run_direct;
  t.push_back(direct);

  MethodDescriptor two_step;
  two_step.name = "two-step";
  two_step.takes_frf = two_step.takes_records = true;
  two_step.preconditions = {
      {"one driven model input per time record", "needs exactly one driven model input", {"auto"}},
      {"at least 20 samples of a record per coefficient of the model's order", "samples are too few for an", {"auto"}}};
  two_step.options = two_step_options();
  two_step.run = run_two_step;
  t.push_back(two_step);

  MethodDescriptor hybrid;
  hybrid.name = "hybrid";
  hybrid.takes_frf = hybrid.takes_records = true;
  hybrid.preconditions = direct_preconditions();
  hybrid.run = run_hybrid;
  t.push_back(hybrid);

  MethodDescriptor ekf;
  ekf.name = "ekf";
  ekf.takes_records = true;
  ekf.needs = "time records (sampled inputs and outputs)";
  ekf.options = ekf_options();
  ekf.run = run_ekf;
  t.push_back(ekf);

  MethodDescriptor arx;
  arx.name = "arx-two-stage";
  arx.takes_records = true;
  arx.needs = "time records (sampled inputs and outputs)";
  arx.preconditions = {
      {"displacement outputs that determine every coordinate", "needs every coordinate measured as a displacement",
       {"auto", "ekf"}},
      {"the mass matrix known (no estimated parameter in M)", "needs the mass matrix known", {"auto", "ekf"}},
      {"records that share one sampling interval and their `# set` values", "fits one ARX model to all records",
       {"auto", "ekf"}}};
  arx.run = run_arx_two_stage;
  t.push_back(arx);

  MethodDescriptor modal;
  modal.name = "modal";
  modal.takes_frf = true;
  modal.needs = "FRFs (it identifies modes from them)";
  modal.preconditions = {
      {"estimated parameters that each act on M or K alone, or on C alone", "needs each parameter to act on damping "
       "alone or on mass/stiffness alone", {"auto"}},
      {"estimated parameters outside the input and output maps", "enters the input or output map", {"auto"}},
      // The numbers the identified modes give fall short: said for one configuration or several.
      {"enough identified modes for the parameters to estimate", "--method modal: the FRFs show ", {"auto"}},
      {"enough identified modes for the parameters to estimate", " configurations show ", {"auto"}}};
  modal.run = run_modal;
  t.push_back(modal);

  MethodDescriptor eiv;
  eiv.name = "eiv";
  eiv.help = "errors in variables: a noisy measured force";
  eiv.takes_records = true;
  eiv.needs = "time records (the measured force's own spectrum and noise)";
  eiv.preconditions = {{"a record long enough for its spectra", "--method eiv needs a longer record",
                        {"time-output-error"}}};
  eiv.run = run_eiv;
  t.push_back(eiv);
  return t;
}

// "a, b or c".
std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return out;
}

}  // namespace

const std::vector<MethodDescriptor>& method_table() {
  static const std::vector<MethodDescriptor> table = make_table();
  return table;
}

const MethodDescriptor* find_method(const std::string& name) {
  for (const MethodDescriptor& m : method_table())
    if (m.name == name) return &m;
  return nullptr;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const MethodDescriptor& m : method_table()) names.push_back(m.name);
  return names;
}

const MethodOption* find_method_option(const std::string& flag) {
  for (const MethodDescriptor& m : method_table())
    for (const MethodOption& o : m.options)
      if (o.flag == flag) return &o;
  return nullptr;
}

std::string data_refusal(const MethodDescriptor& method, const DataSet& d) {
  const bool frf = d.is_frf();
  if (frf ? method.takes_frf : method.takes_records) return "";
  std::vector<std::string> others;
  for (const MethodDescriptor& m : method_table())
    if (frf ? m.takes_frf : m.takes_records) others.push_back(m.name);
  return d.file() + ": error: --method " + method.name + " needs " + method.needs +
         (frf ? ", but this file holds FRFs" : ", but this is a time record") + "\nnote: methods that take " +
         (frf ? "FRFs" : "time records") + ": " + listed(others);
}

std::string preconditions_note(const MethodDescriptor& method, const std::string& message) {
  std::string out;
  for (const MethodPrecondition& p : method.preconditions)
    if (message.find(p.refusal) != std::string::npos)
      out += std::string(out.empty() ? "" : "\n") + "note: --method " + listed(p.instead) +
             " does without " + p.needs;
  return out;
}

}  // namespace mbgen
