#include "symbolic/derive.hpp"

#include "frontend/diagnostics.hpp"
#include "symbolic/blocks.hpp"
#include "symbolic/checks.hpp"
#include "symbolic/geometry.hpp"
#include "symbolic/lagrange.hpp"
#include "symbolic/mechanism.hpp"
#include "symbolic/output_filters.hpp"
#include "symbolic/to_ginac.hpp"
#include "symbolic/transfer_functions.hpp"

namespace mbgen::symbolic {

namespace {

void tidy_all(GiNaC::matrix& mat) {
  for (unsigned i = 0; i < mat.rows(); ++i)
    for (unsigned j = 0; j < mat.cols(); ++j) mat(i, j) = tidy(mat(i, j));
}

}  // namespace

SymbolicModel derive(const ir::ModelIr& model, const DeriveOptions& options) {
  if (model.bodies.empty())
    throw frontend::ModelError(model.file, {},
                               "the model has no bodies, so there are no equations of motion to derive (is the file "
                               "empty, or only comments?)");
  const ParameterTable params(model, options.set);
  const Mechanism mech = make_mechanism(model, params);
  SymbolicModel sm;
  sm.model = &model;
  sm.parameters = params.free_parameters();
  for (const ir::Body& b : model.bodies)
    for (ir::Dof d : b.dofs) sm.coordinates.push_back({b.name, d, ""});
  const unsigned n = static_cast<unsigned>(mech.coordinate_count);
  const unsigned inputs = static_cast<unsigned>(model.inputs.size());
  const unsigned outputs = static_cast<unsigned>(model.outputs.size());
  sm.M = sm.C = sm.G = sm.K = GiNaC::matrix(n, n);
  sm.B = GiNaC::matrix(n, inputs);
  sm.Cd = sm.Cv = sm.Ca = GiNaC::matrix(outputs, n);

  add_kinetic_energy(mech, sm);
  add_spring_dampers(mech, sm);
  add_inputs_outputs(mech, sm);
  add_output_filters(params, sm);
  for (GiNaC::matrix* mat : {&sm.M, &sm.C, &sm.G, &sm.K, &sm.B, &sm.Cd, &sm.Cv, &sm.Ca}) tidy_all(*mat);
  sm.C_total = sm.C.add(sm.G);
  tidy_all(sm.C_total);

  check_every_coordinate_is_held(mech, sm);
  check_mass_matrix(mech, sm);
  sm.blocks = uncoupled_blocks({&sm.M, &sm.C_total, &sm.K}, static_cast<int>(sm.coordinates.size()));
  if (options.transfer_functions) add_transfer_functions(sm);
  return sm;
}

}  // namespace mbgen::symbolic
