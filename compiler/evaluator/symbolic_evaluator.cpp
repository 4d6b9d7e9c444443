#include "evaluator/symbolic_evaluator.hpp"

#include "frontend/diagnostics.hpp"

#include <stdexcept>

#include "symbolic/to_ginac.hpp"

namespace mbgen::evaluator {

namespace {

ParameterRole runtime_role(ir::Role r) {
  switch (r) {
    case ir::Role::Estimate: return ParameterRole::Estimate;
    case ir::Role::Fixed: return ParameterRole::Fixed;
    case ir::Role::Known: break;
  }
  return ParameterRole::Known;
}

double to_double(const GiNaC::ex& e) {
  const GiNaC::ex v = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::runtime_error("evaluator: a value is not a number");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

ModelInfo make_info(const symbolic::SymbolicModel& sym) {
  ModelInfo info;
  info.name = sym.model->name;
  // Bounds may be expressions of parameters: evaluate them at the model's values.
  const symbolic::ParameterTable table(*sym.model);
  const GiNaC::exmap values = sym.values();
  for (const symbolic::FreeParameter& fp : sym.parameters) {
    ParameterInfo p;
    p.name = fp.name;
    p.value = to_double(fp.value);
    if (fp.ir) {
      p.role = runtime_role(fp.ir->role);
      p.unit = fp.ir->unit;
      // Without pattern matching, GiNaC looks each symbol up in the map instead of trying every entry at every
      // node: quadratic in the number of parameters otherwise (cpp_emitter.cpp's bounds_of says the same).
      if (fp.ir->lower) p.lower = to_double(table.convert(*fp.ir->lower).subs(values, GiNaC::subs_options::no_pattern));
      if (fp.ir->upper) p.upper = to_double(table.convert(*fp.ir->upper).subs(values, GiNaC::subs_options::no_pattern));
    }
    info.parameters.push_back(p);
  }
  for (const symbolic::Coordinate& c : sym.coordinates) info.coordinates.push_back(c.name());
  for (const ir::Input& in : sym.model->inputs) info.inputs.push_back(in.name);
  for (const ir::Output& out : sym.model->outputs) info.outputs.push_back(out.name);
  return info;
}

}  // namespace

SymbolicEvaluator::SymbolicEvaluator(const symbolic::SymbolicModel& sym) : info_(make_info(sym)) {
  n_ = static_cast<int>(sym.coordinates.size());
  const GiNaC::matrix* matrices[kMatrixCount] = {&sym.M, &sym.C_total, &sym.K, &sym.B, &sym.Cd, &sym.Cv, &sym.Ca};
  std::vector<GiNaC::symbol> params;
  for (const symbolic::FreeParameter& fp : sym.parameters) params.push_back(fp.sym);

  std::vector<GiNaC::ex> value_exprs, derivative_exprs;
  for (int m = 0; m < kMatrixCount; ++m) {
    const GiNaC::matrix& A = *matrices[m];
    for (unsigned r = 0; r < A.rows(); ++r)
      for (unsigned c = 0; c < A.cols(); ++c) {
        const GiNaC::ex& e = A(r, c);
        if (e.is_zero()) continue;
        value_slots_.push_back({static_cast<Matrix>(m), static_cast<int>(r), static_cast<int>(c), -1});
        value_exprs.push_back(e);
        for (std::size_t j = 0; j < params.size(); ++j) {
          const GiNaC::ex d = e.diff(params[j]);
          if (d.is_zero()) continue;
          derivative_slots_.push_back({static_cast<Matrix>(m), static_cast<int>(r), static_cast<int>(c), static_cast<int>(j)});
          derivative_exprs.push_back(d);
        }
      }
  }
  values_ = std::make_unique<ExpressionTape>(params, value_exprs);
  derivatives_ = std::make_unique<ExpressionTape>(params, derivative_exprs);
}

void SymbolicEvaluator::check_size(const Eigen::VectorXd& p) const {
  if (p.size() != static_cast<Eigen::Index>(info_.parameters.size()))
    throw std::invalid_argument("model `" + info_.name + "` has " + std::to_string(info_.parameters.size()) +
                                " parameters, got a vector of " + std::to_string(p.size()));
}

void SymbolicEvaluator::evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const {
  check_size(p);
  const Eigen::Index n = n_, ni = static_cast<Eigen::Index>(info_.inputs.size()),
                     no = static_cast<Eigen::Index>(info_.outputs.size());
  out.M.setZero(n, n);
  out.C.setZero(n, n);
  out.K.setZero(n, n);
  out.B.setZero(n, ni);
  out.Cd.setZero(no, n);
  out.Cv.setZero(no, n);
  out.Ca.setZero(no, n);
  Eigen::MatrixXd* targets[kMatrixCount] = {&out.M, &out.C, &out.K, &out.B, &out.Cd, &out.Cv, &out.Ca};
  std::vector<double> v;
  values_->evaluate(p.data(), v);
  for (std::size_t i = 0; i < value_slots_.size(); ++i) {
    const Slot& s = value_slots_[i];
    (*targets[s.matrix])(s.row, s.col) = v[i];
  }
}

void SymbolicEvaluator::derivatives(const Eigen::VectorXd& p, ModelDerivatives& out) const {
  check_size(p);
  std::vector<DerivativeEntry>* targets[kMatrixCount] = {&out.M, &out.C, &out.K, &out.B, &out.Cd, &out.Cv, &out.Ca};
  for (auto* t : targets) t->clear();
  std::vector<double> v;
  derivatives_->evaluate(p.data(), v);
  for (std::size_t i = 0; i < derivative_slots_.size(); ++i) {
    const Slot& s = derivative_slots_[i];
    targets[s.matrix]->push_back({s.param, s.row, s.col, v[i]});
  }
}

std::unique_ptr<mbgen::Model> make_evaluator(const ir::ModelIr& model, const symbolic::DeriveOptions& options) {
  symbolic::DeriveOptions o = options;
  o.transfer_functions = false;  // the runtime computes responses numerically
  const symbolic::SymbolicModel sym = symbolic::derive(model, o);
  try {
    return std::make_unique<SymbolicEvaluator>(sym);
  } catch (const UnsupportedExpression& e) {
    // A valid model the numeric evaluator cannot run (a parameter in an exponent): the model's limit, not a bug.
    throw frontend::ModelError(model.file, {}, std::string("cannot fit or simulate this model: ") + e.what());
  }
}

}  // namespace mbgen::evaluator
