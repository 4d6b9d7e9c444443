// What every extension operator needs: the model it extends (parsed from its text, so source locations point
// into that text), the diagnosis context, and a Draft that builds one candidate's model and text side by side.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "diagnosis/extension.hpp"
#include "diagnosis/model_values.hpp"
#include "diagnosis/names.hpp"
#include "diagnosis/text_patch.hpp"
#include "numerics/constants.hpp"

namespace mbgen::diagnosis {

struct OperatorInput {
  const ir::ModelIr& model;  // parsed from `text`
  const std::string& text;
  const ExtensionContext& ctx;
  ModelValues values;  // the model's values, ctx.values overriding
};

// A candidate whose start values are not finite at the current estimate (a fit that drove a mass or a damping to its
// bound of zero on a few lines leaves a new mode's frequency, or a ratio, without a value): the operator offers no
// candidate then (enumerate_extensions skips it) rather than writing `inf` into a model.
class UnusableStart : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One candidate under construction. Declarations added through it go both into the extended model (appended to
// their list, as the parser would read them from the end of the text) and into the end section of the text.
class Draft {
 public:
  Draft(const OperatorInput& in, const std::string& operator_name, const std::string& target);

  ir::ModelIr& model() { return ext_.model; }
  NameSet& names() { return names_; }
  TextPatch& patch() { return patch_; }

  // A new parameter with role estimate (or `role`), start `value`, optional bounds; returns its (fresh) name.
  std::string add_parameter(const std::string& base, double value, const std::string& unit,
                            std::optional<double> lower, std::optional<double> upper, const std::string& why,
                            ir::Role role = ir::Role::Estimate);
  // A new parameter declared as given (its name taken from names()); `why` becomes its comment in the text.
  void add_parameter(ir::Parameter p, const std::string& why);
  void add_ground(ir::Ground g);
  void add_body(ir::Body b);
  void add_element(ir::Element e);
  void add_spin(ir::Spin s);
  void add_filter(ir::Filter f);
  void free_parameter(const std::string& name) { ext_.freed_parameters.push_back(name); }
  void set_variant(const std::string& variant) { ext_.variant = variant; }
  void set_start_from_variant(Extension::VariantStart start) { ext_.start_from_variant = std::move(start); }
  void add_resonating_body(const std::string& body) { ext_.resonating_bodies.push_back(body); }
  // Extension::nesting: new parameter `name` at `value` gives the current model back.
  void nests_at(const std::string& name, double value) { ext_.nesting[name] = value; }
  // The same for a parameter that gives the current model back at its lower bound of zero (a joining spring's
  // stiffness): a bounded fit approaches zero by factors and cannot start on it, so it starts at kNearZero times
  // its start value, where the new element's effect is that small.
  static constexpr double kNearZero = 1e-4;
  void nests_near_zero(const std::string& name, double start) { ext_.nesting[name] = kNearZero * start; }

  Extension finish(const std::string& description);

 private:
  Extension ext_;
  NameSet names_;
  TextPatch patch_;
  std::string declarations_;  // parameters first, then the rest, for the end section
  std::string statements_;
};

// ---- shared facts about a model ----------------------------------------------------------------------------

// The signal that marks where a body is measured or excited: its first input, else its first output.
struct SignalPoint {
  std::string signal;         // input or output name
  bool is_input = false;
  const ir::Attachment* at;   // point filled by the front end (explicit or the centre of mass)
  const ir::Direction* direction;
};
std::optional<SignalPoint> signal_point(const ir::ModelIr& model, const std::string& body);

// The global axis (0, 1, 2) a direction lies along, if it does (a vector is evaluated at the current values).
std::optional<int> axis_of(const ir::Direction& d, const ModelValues& values);

bool has_dof(const ir::Body& b, ir::Dof d);
double total_moving_mass(const ir::ModelIr& model, const ModelValues& values);
// The largest stiffness value of the translational elements (spring, spring3); 0 if there are none.
double largest_translational_stiffness(const ir::ModelIr& model, const ModelValues& values);
double smallest_body_mass(const ir::ModelIr& model, const ModelValues& values);

// A point body `name` (fresh) of mass `mass` at `point`, with one coordinate along global axis `axis`, held to
// `frame` at the same point by a spring-damper (`stiffness`, `damping`) along that axis, named `name` + `suffix`:
// a resonator's mass, a sensor on its mounting. Returns the body's name.
std::string add_body_on_axial_spring(Draft& d, const std::string& name, const std::string& mass, const ir::Vec3& point,
                                     int axis, const std::string& frame, const std::string& suffix,
                                     const std::string& stiffness, const std::string& damping);

// Start value of a damping for stiffness k on mass m: 2 % of critical damping, c = 2*0.02*sqrt(k*m).
double light_damping(double k, double m);
using numerics::kTwoPi;

// ---- the operators (one file each; docs/extensions.md) -------------------------------------------------------
std::vector<Extension> measurement_chain(const OperatorInput& in);
std::vector<Extension> compliant_ground(const OperatorInput& in);
std::vector<Extension> gyroscopic(const OperatorInput& in);
std::vector<Extension> free_parameter(const OperatorInput& in);
std::vector<Extension> untie_parameter(const OperatorInput& in);
std::vector<Extension> moment_stiffness(const OperatorInput& in);
std::vector<Extension> added_mass(const OperatorInput& in);
std::vector<Extension> resonator(const OperatorInput& in);
std::vector<Extension> sensor_dynamics(const OperatorInput& in);
std::vector<Extension> connection(const OperatorInput& in);

}  // namespace mbgen::diagnosis
