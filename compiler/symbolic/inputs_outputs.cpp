// Generalized forces of the inputs and the sensor rows of the outputs (thesis Sec. 3.4.5, 3.4.6).
#include "frontend/diagnostics.hpp"
#include "symbolic/lagrange.hpp"

namespace mbgen::symbolic {

void add_inputs_outputs(const Mechanism& m, SymbolicModel& out) {
  const ir::ModelIr& model = *m.model;
  for (size_t u = 0; u < model.inputs.size(); ++u) {
    const ir::Input& in = model.inputs[u];
    if (!m.find(in.at.frame))
      throw frontend::ModelError(model.file, in.loc,
                                 "input `" + in.name + "` acts on `" + in.at.frame +
                                     "`, which is not a body; an input must act on a body");
    const GiNaC::matrix n = unit_direction(in.direction, *m.params);
    // Virtual work F . dr_p = (dr_p/dq)^T F . dq for a force, M . dtheta for a moment.
    const Row b = in.kind == ir::InputKind::Force ? displacement_row(m, in.at, n) : moment_row(m, in.at.frame, n);
    // The record reads `gain` times the applied force, so per unit of the recorded input the structure is driven by
    // 1/gain: the column is divided (and so is every product built from B, with its parameter derivatives).
    GiNaC::ex gain = 1;
    if (in.gain) {
      const GiNaC::ex g = m.params->convert(*in.gain);
      if (GiNaC::evalf(g.subs(m.params->values())).is_zero())
        throw frontend::ModelError(model.file, in.gain->loc,
                                   "input `{}`: its gain is 0 at the parameters' values: its record would read no "
                                   "force",
                                   in.name);
      gain = g;
    }
    for (int i = 0; i < m.coordinate_count; ++i) out.B(i, u) = in.gain ? b[i] / gain : b[i];
  }
  for (size_t o = 0; o < model.outputs.size(); ++o) {
    const ir::Output& y = model.outputs[o];
    if (!m.find(y.at.frame))
      throw frontend::ModelError(model.file, y.loc,
                                 "output `" + y.name + "` measures `" + y.at.frame +
                                     "`, which is not a body; an output must measure a body");
    const Row c = displacement_row(m, y.at, unit_direction(y.direction, *m.params));
    GiNaC::matrix& target = y.kind == ir::OutputKind::Displacement ? out.Cd
                            : y.kind == ir::OutputKind::Velocity   ? out.Cv
                                                                   : out.Ca;
    for (int i = 0; i < m.coordinate_count; ++i) target(o, i) = c[i];
  }
}

}  // namespace mbgen::symbolic
