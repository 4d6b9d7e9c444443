#include "cli/method_option.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <mbgen/methods/hybrid.hpp>
#include <mbgen/methods/modal_start.hpp>

#include "cli/number_checks.hpp"
#include "elimination/analytical_solver.hpp"

namespace mbgen::cli {

std::string method_help() {
  const std::vector<MethodDescriptor>& table = method_table();
  std::string out;
  for (std::size_t i = 0; i < table.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + table[i].name;
    if (!table[i].help.empty()) out += " (" + table[i].help + ")";
  }
  return out + "; docs/methods.md";
}

void add_method_choice(CLI::App& app, std::string& name, const std::string& help_lead) {
  app.add_option("--method", name, help_lead + method_help())->check(CLI::IsMember(method_names()));
}

void add_method_own_options(CLI::App& app, MethodOptions& options) {
  for (const MethodDescriptor& m : method_table())
    for (const MethodOption& o : m.options) {
      if (o.kind == MethodOption::Kind::Choice)
        app.add_option(o.flag, o.text(options), o.help)->check(CLI::IsMember(o.choices));
      else
        app.add_option(o.flag, o.number(options), o.help)->check(non_negative_number());
    }
}

std::string method_options_digest(MethodOptions options) {
  std::string out;
  for (const MethodDescriptor& m : method_table())
    for (const MethodOption& o : m.options) {
      char number[32];
      std::snprintf(number, sizeof number, "%.17g", o.number ? o.number(options) : 0.0);
      out += ", " + o.flag + " " + (o.kind == MethodOption::Kind::Choice ? o.text(options) : std::string(number));
    }
  return out;
}

const MethodDescriptor& method_named(const std::string& name, const std::string& command) {
  const MethodDescriptor* const method = find_method(name);
  if (!method) throw FitError(command + ": no method `" + name + "` (--method takes " + method_help() + ")");
  return *method;
}

void check_method_takes(const MethodDescriptor& method, const std::vector<DataSet>& data) {
  for (const DataSet& d : data)
    if (const std::string refusal = data_refusal(method, d); !refusal.empty()) throw FitError(refusal);
}

std::function<AnalyticalSolver()> analytical_solver(const ir::ModelIr& model, const symbolic::DeriveOptions& derive) {
  return [&model, &derive] {
    symbolic::DeriveOptions d = derive;
    d.transfer_functions = false;  // derived per pair, as the solver needs them
    return elimination::make_analytical_solver(std::make_shared<const symbolic::SymbolicModel>(symbolic::derive(model, d)));
  };
}

FitResult run_method(const MethodDescriptor& method, const MethodRun& run) {
  try {
    return method.run(run);
  } catch (const FitError& e) {
    const std::string note = preconditions_note(method, e.what());
    if (note.empty()) throw;
    throw FitError(std::string(e.what()) + "\n" + note);
  }
}

std::map<std::string, double> estimate_as_start(const Model& model, const FitResult& result) {
  const ModelInfo& info = model.info();
  std::map<std::string, double> start;
  for (const ParameterEstimate& e : result.parameters) {
    if (!e.estimated || !std::isfinite(e.value)) continue;
    start[e.name] = start_inside_bounds(e, info.parameters[static_cast<std::size_t>(info.parameter_index(e.name))]);
  }
  return start;
}

void add_start(const std::map<std::string, double>& values, FitOptions& options) {
  if (values.empty()) return;
  const int starts = options.starts;
  start_first_at(values, options);
  options.starts = starts + 1;
}

}  // namespace mbgen::cli
