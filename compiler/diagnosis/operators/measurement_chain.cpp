// measurement_chain -- the data are right about the structure but wrong about what they are: a sensor's calibration
// or polarity, two cables swapped, a force transducer's calibration or sign. These come first in a diagnosis
// (docs/diagnosis.md, "The measurement chain first"): a structural extension must never stand in for them.
//
//   measurement_chain:gain:O     O reads g times the truth (a `filter ... gain` on O). Three variants:
//                                "calibration" (g > 0, started at 1: a sensitivity error, or a unit mix-up when g
//                                is near 1000, 1/1000, 9.81 or 1/9.81), "polarity" (g < 0, started at -1: the sensor
//                                mounted reversed, or its sign wired wrong, and its size off too) and "reversed"
//                                (g = -1, no new parameter: the sign alone). BIC chooses between the last two: the
//                                sign alone wins where the data do not show a size besides it (a reversed sensor of
//                                the right sensitivity, or a size the structure's scale stands in for).
//   measurement_chain:swap:A,B   the columns of outputs A and B exchanged (two cables swapped): the two output
//                                statements exchange their names. No new parameter. Offered for outputs of one kind
//                                (displacement, velocity, acceleration) without filters of their own.
//   measurement_chain:form:O     O's data are another form of its quantity: a mobility or an accelerance exported
//                                where the model has a receptance, or the other way round (a factor (i w)^k, not a
//                                constant). Variants "displacement", "velocity", "acceleration": the output
//                                statement measures that instead. No new parameter.
//   measurement_chain:input:F    the recorded force is g times the applied one. Variants "calibration" (g > 0,
//                                started at 1), "polarity" (g < 0, started at -1: a reaction mass's force computed
//                                with the wrong sign) and "reversed" (F's direction reversed, no new parameter: with
//                                every mass, stiffness and damping estimated, the data cannot tell g's size from the
//                                structure's scale). With one input every FRF is divided by g: a gain 1/g on every
//                                output. With several, only F's columns are: the input statement gets `gain g` (times
//                                its gain, if it has one), and g's size is told apart from the structure's scale by
//                                the other inputs' columns.
//
// None of these is a new body or element; the structure's parameters stay as they are.
#include <algorithm>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"
#include "frontend/model_writer.hpp"

namespace mbgen::diagnosis {

namespace {

struct Sign {
  const char* variant;
  double start;
  std::optional<double> lower, upper;
};
const Sign kCalibration{"calibration", 1.0, 0.0, std::nullopt};
const Sign kPolarity{"polarity", -1.0, std::nullopt, 0.0};

bool has_filter(const ir::ModelIr& model, const std::string& output) {
  return std::any_of(model.filters.begin(), model.filters.end(),
                     [&](const ir::Filter& f) { return f.output == output; });
}

ir::Filter gain_filter(Draft& d, const std::string& output, ir::Expr factor) {
  ir::Filter f;
  f.name = d.names().fresh("chain_" + output);
  f.output = output;
  f.kind = ir::FilterKind::Gain;
  f.factor = std::move(factor);
  return f;
}

Extension output_gain(const OperatorInput& in, const ir::Output& out, const Sign& sign) {
  Draft d(in, "measurement_chain", "gain:" + out.name);
  d.set_variant(sign.variant);
  const std::string g = d.add_parameter("g_" + out.name, sign.start, "", sign.lower, sign.upper,
                                        "what " + out.name + " reads per unit of the structure's motion");
  d.add_filter(gain_filter(d, out.name, sym(g)));
  return d.finish(out.name + (sign.start > 0 ? " reads a constant factor " : " reads with the opposite sign, times ") +
                  g + " of the structure's motion: its sensor's " +
                  (sign.start > 0 ? "calibration (or units)" : "polarity (mounted or wired reversed)"));
}

Extension reversed_output(const OperatorInput& in, const ir::Output& out) {
  Draft d(in, "measurement_chain", "gain:" + out.name);
  d.set_variant("reversed");
  d.add_filter(gain_filter(d, out.name, neg(num("1"))));
  return d.finish(out.name + " reads with the opposite sign: its sensor is mounted or wired reversed");
}

Extension other_form(const OperatorInput& in, const ir::Output& out, ir::OutputKind kind) {
  Draft d(in, "measurement_chain", "form:" + out.name);
  d.set_variant(ir::to_string(kind));
  ir::Output& changed = *std::find_if(d.model().outputs.begin(), d.model().outputs.end(),
                                      [&](const ir::Output& o) { return o.name == out.name; });
  changed.kind = kind;
  d.patch().replace_statement(out.loc, out.name + std::string(" measured as ") + ir::to_string(kind) +
                                           ": its data are that form of the quantity",
                              frontend::write_output(changed));
  const std::string article = kind == ir::OutputKind::Acceleration ? "an " : "a ";
  return d.finish(out.name + "'s data are " + article + ir::to_string(kind) + ", not the " + ir::to_string(out.kind) +
                  " the model reads (" + (kind == ir::OutputKind::Velocity       ? "a mobility"
                                          : kind == ir::OutputKind::Acceleration ? "an accelerance"
                                                                                 : "a receptance") +
                  " exported as the other form)");
}

Extension swapped(const OperatorInput& in, const ir::Output& a, const ir::Output& b) {
  Draft d(in, "measurement_chain", "swap:" + a.name + "," + b.name);
  ir::Output& first = *std::find_if(d.model().outputs.begin(), d.model().outputs.end(),
                                    [&](const ir::Output& o) { return o.name == a.name; });
  ir::Output& second = *std::find_if(d.model().outputs.begin(), d.model().outputs.end(),
                                     [&](const ir::Output& o) { return o.name == b.name; });
  std::swap(first.name, second.name);
  d.patch().replace_statement(a.loc, a.name + " and " + b.name + " exchanged: their cables are swapped",
                              frontend::write_output(first));
  d.patch().replace_statement(b.loc, b.name + " and " + a.name + " exchanged", frontend::write_output(second));
  return d.finish("the columns of " + a.name + " and " + b.name + " are exchanged: two cables swapped");
}

Extension input_gain(const OperatorInput& in, const ir::Input& input, const Sign& sign) {
  Draft d(in, "measurement_chain", "input:" + input.name);
  d.set_variant(sign.variant);
  const std::string g = d.add_parameter("gi_" + input.name, sign.start, "", sign.lower, sign.upper,
                                        "what the record of " + input.name + " reads per unit of the applied force");
  for (const ir::Output& out : in.model.outputs) d.add_filter(gain_filter(d, out.name, div(num("1"), sym(g))));
  return d.finish("the recorded " + input.name + " is " + g + " times the force applied: the force transducer's " +
                  (sign.start > 0 ? "calibration (or units)" : "sign (a reaction force taken with the wrong sign)"));
}

// Several inputs: F's columns alone divided by g, through the input's own gain (docs/language.md, "input ... gain").
Extension recorded_input_gain(const OperatorInput& in, const ir::Input& input, const Sign& sign) {
  Draft d(in, "measurement_chain", "input:" + input.name);
  d.set_variant(sign.variant);
  const std::string g = d.add_parameter("gi_" + input.name, sign.start, "", sign.lower, sign.upper,
                                        "what the record of " + input.name + " reads per unit of the applied force");
  ir::Input& changed = *std::find_if(d.model().inputs.begin(), d.model().inputs.end(),
                                     [&](const ir::Input& i) { return i.name == input.name; });
  changed.gain = changed.gain ? mul(*changed.gain, sym(g)) : sym(g);
  const std::string why = sign.start > 0 ? " reads " + g + " times the force applied: its transducer's calibration"
                                         : " reads " + g + " (negative) times the force applied: its sign";
  d.patch().replace_statement(input.loc, input.name + why, frontend::write_input(changed));
  return d.finish("the recorded " + input.name + " is " + g + " times the force applied: the force transducer's " +
                  (sign.start > 0 ? "calibration (or units)" : "sign (a reaction force taken with the wrong sign)"));
}

Extension reversed_input(const OperatorInput& in, const ir::Input& input) {
  Draft d(in, "measurement_chain", "input:" + input.name);
  d.set_variant("reversed");
  ir::Input& changed = *std::find_if(d.model().inputs.begin(), d.model().inputs.end(),
                                     [&](const ir::Input& i) { return i.name == input.name; });
  changed.direction.axis.clear();
  for (ir::Expr& c : changed.direction.vector)
    if (!(c.kind == ir::Expr::Kind::Number && c.text == "0")) c = neg(c);
  changed.direction.loc = {};
  d.patch().replace_statement(input.loc, input.name + " reversed: the force was recorded with the wrong sign",
                              frontend::write_input(changed));
  return d.finish("the recorded " + input.name + " has the opposite sign of the force applied");
}

}  // namespace

std::vector<Extension> measurement_chain(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Output& o : in.model.outputs) {
    for (const Sign& sign : {kCalibration, kPolarity}) out.push_back(output_gain(in, o, sign));
    out.push_back(reversed_output(in, o));
  }
  for (const ir::Output& o : in.model.outputs)
    for (ir::OutputKind kind : {ir::OutputKind::Displacement, ir::OutputKind::Velocity, ir::OutputKind::Acceleration})
      if (kind != o.kind) out.push_back(other_form(in, o, kind));
  const auto& outputs = in.model.outputs;
  for (std::size_t i = 0; i < outputs.size(); ++i)
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
      if (outputs[i].kind == outputs[j].kind && !has_filter(in.model, outputs[i].name) &&
          !has_filter(in.model, outputs[j].name))
        out.push_back(swapped(in, outputs[i], outputs[j]));
  // One input: a gain 1/g on every output (the same FRFs as a gain g on the input).
  if (in.model.inputs.size() == 1) {
    for (const Sign& sign : {kCalibration, kPolarity}) out.push_back(input_gain(in, in.model.inputs.front(), sign));
    out.push_back(reversed_input(in, in.model.inputs.front()));
  } else {
    for (const ir::Input& input : in.model.inputs) {
      for (const Sign& sign : {kCalibration, kPolarity}) out.push_back(recorded_input_gain(in, input, sign));
      out.push_back(reversed_input(in, input));
    }
  }
  return out;
}

}  // namespace mbgen::diagnosis
