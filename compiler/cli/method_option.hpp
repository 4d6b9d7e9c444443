// --method and the methods' own options (docs/cli.md, docs/methods.md), as fit, diagnose and monitor take them: the
// choices, help texts and options all read from the method table (mbgen/methods/method_table.hpp). fit runs the
// method; diagnose and monitor judge by output error, so there the method's estimate becomes one more start of
// their output-error fits.
#pragma once

#include <CLI/CLI.hpp>
#include <mbgen/methods/method_table.hpp>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

// --method's help: the table's methods with their few words.
std::string method_help();

// --method NAME, checked against the table; `help_lead` comes before the list of methods.
void add_method_choice(CLI::App& app, std::string& name, const std::string& help_lead = "");

// Every method's own options (--two-step-route, --ekf-drift, ...), bound to their members of `options`.
void add_method_own_options(CLI::App& app, MethodOptions& options);

// Every method option's flag and value, ", --two-step-route auto, ...": what a result depends on (a fleet item's
// digest).
std::string method_options_digest(MethodOptions options);

// The method called `name`, or a FitError naming the choices.
const MethodDescriptor& method_named(const std::string& name, const std::string& command);

// Refuses data the method cannot use (status 1), with the refusal fit gives.
void check_method_takes(const MethodDescriptor& method, const std::vector<DataSet>& data);

// two-step's exact solver, made when its route may take it: GiNaC's on the model's symbolic coefficients, which the
// runtime cannot make for lack of computer algebra. `model` and `derive` must outlive the returned factory's calls.
std::function<AnalyticalSolver()> analytical_solver(const ir::ModelIr& model, const symbolic::DeriveOptions& derive);

// Runs the method; a refusal of data it cannot use is followed by a note naming the methods that do without what
// it lacks.
FitResult run_method(const MethodDescriptor& method, const MethodRun& run);

// The estimate of `result` as an output-error start: the parameters it estimated, by name; one left at a bound
// starts just inside it (a bound is the edge of the output-error fit's reparameterisation).
std::map<std::string, double> estimate_as_start(const Model& model, const FitResult& result);

// `values` as one more start of the output-error search: the first chosen start (the others follow it), with one
// start more, so that no start it had is lost.
void add_start(const std::map<std::string, double>& values, FitOptions& options);

}  // namespace mbgen::cli
