// The estimation methods as one table (runtime/src/methods/README.md; docs/methods.md): what `mbgen fit --method`
// (and diagnose's and monitor's, where the estimate starts their output-error fits) offers, the data each method
// takes, what else it needs, its options and how it runs. The CLI reads the table for --method's choices and help,
// its options, its refusals and its dispatch, so a method is added in one place.
//
//   const MethodDescriptor* m = mbgen::find_method("two-step");
//   FitResult r = m->run({model, data, fit_options, method_options});
//
// Output error (mbgen::fit) is in the table as "auto" (the domain by the data), "frf-output-error" and
// "time-output-error"; the others are the methods of runtime/include/mbgen/methods.
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/methods/ekf.hpp"
#include "mbgen/methods/two_step.hpp"

#include <functional>
#include <string>
#include <vector>

namespace mbgen {

// The options of all methods, typed, with their defaults (each method reads its own).
struct MethodOptions {
  // two-step: step two's route as --two-step-route says it: "auto", "analytical", "numerical" or "minimisation".
  std::string two_step_route = "auto";
  TwoStepOptions two_step;  // its `solver` and `analytical` are set from two_step_route and analytical_solver
  EkfOptions ekf;
  // two-step's exact solver of the coefficient equations, made only when the route may take it (deriving it costs a
  // symbolic derivation); empty: the runtime has no computer algebra and the analytical route is unavailable.
  std::function<AnalyticalSolver()> analytical_solver;
};

// One option of a method, as the command line takes it: a choice among names or a number of at least 0.
struct MethodOption {
  enum class Kind { Choice, NonNegativeNumber };
  std::string flag;                  // "--two-step-model"
  std::string help;                  // the help text, with the default
  Kind kind = Kind::Choice;
  std::vector<std::string> choices;  // Kind::Choice: the names it takes
  // Where the value lives in MethodOptions (the member that fits the kind; the other is null).
  std::string& (*text)(MethodOptions&) = nullptr;
  double& (*number)(MethodOptions&) = nullptr;
};

// What a method needs beyond the kind of data, how its refusal reads when the data lack it, and the methods that do
// without: a refusal that shows `refusal` is followed by a note naming them.
struct MethodPrecondition {
  std::string needs;                 // "the mass matrix known (no estimated parameter in M)"
  std::string refusal;               // a part of the method's refusal text: "needs the mass matrix known"
  std::vector<std::string> instead;  // methods that do not need it, e.g. {"auto", "ekf"}
};

// What a method's run gets.
struct MethodRun {
  const Model& model;
  const std::vector<DataSet>& data;
  const FitOptions& fit;
  const MethodOptions& options;
};

struct MethodDescriptor {
  std::string name;  // as --method takes it
  std::string help;  // a few words after the name in --method's help; "" for none
  // The kinds of data it takes, and what it says it needs when given the other kind ("time records (sampled inputs
  // and outputs)"): the refusal reads "FILE: error: --method NAME needs <needs>, but this file holds FRFs".
  bool takes_frf = false;
  bool takes_records = false;
  std::string needs;
  std::vector<MethodPrecondition> preconditions;
  bool output_error = false;  // the output-error search (mbgen::fit): --start-from-modes applies to it
  std::vector<MethodOption> options;
  FitResult (*run)(const MethodRun&) = nullptr;
};

// All methods, in the order --method's help lists them.
const std::vector<MethodDescriptor>& method_table();

// The method called `name`; nullptr for none.
const MethodDescriptor* find_method(const std::string& name);

// The names of method_table(), in its order.
std::vector<std::string> method_names();

// The option of any method with this flag ("--ekf-drift"); nullptr for none.
const MethodOption* find_method_option(const std::string& flag);

// "" when `method` takes data set `d`; otherwise the refusal "FILE: error: --method NAME needs ..., but this ...",
// followed by the methods that take that kind of data.
std::string data_refusal(const MethodDescriptor& method, const DataSet& d);

// For a refusal `message` from `method`'s run: a note naming the methods that do without what it lacks (those of
// each precondition whose `refusal` the message shows); "" when it shows none.
std::string preconditions_note(const MethodDescriptor& method, const std::string& message);

}  // namespace mbgen
