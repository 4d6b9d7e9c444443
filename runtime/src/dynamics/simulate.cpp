#include "mbgen/simulate.hpp"

#include "model_checks.hpp"
#include "mbgen/dynamics_error.hpp"

#include <sstream>

namespace mbgen {
namespace {

void check_inputs(const Eigen::MatrixXd& inputs, Eigen::Index expected, const char* where) {
  if (inputs.cols() != expected) {
    std::ostringstream msg;
    msg << where << ": the input record has " << inputs.cols() << " columns, the model has " << expected
        << " inputs";
    throw DynamicsError(msg.str());
  }
  if (!inputs.allFinite()) throw DynamicsError(std::string(where) + ": the input record has non-finite values");
}

}  // namespace

Eigen::MatrixXd simulate(const DiscreteStateSpace& system, const Eigen::MatrixXd& inputs) {
  check_inputs(inputs, system.Gamma0.cols(), "simulate");
  const Eigen::Index samples = inputs.rows();
  const Eigen::MatrixXd U = inputs.transpose();  // one column per sample: contiguous access in the loop
  Eigen::MatrixXd Y(system.C.rows(), samples);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.Phi.rows()), next(system.Phi.rows());
  const bool first_order = system.hold == InputHold::FirstOrder;
  for (Eigen::Index k = 0; k < samples; ++k) {
    Y.col(k).noalias() = system.C * x;
    Y.col(k).noalias() += system.D * U.col(k);
    if (k + 1 == samples) break;
    next.noalias() = system.Phi * x;
    next.noalias() += system.Gamma0 * U.col(k);
    if (first_order) next.noalias() += system.Gamma1 * U.col(k + 1);
    x.swap(next);
  }
  return Y.transpose();
}

Eigen::MatrixXd simulate(const ModelMatrices& m, const Eigen::MatrixXd& inputs, double dt, InputHold hold) {
  return simulate(discretize(state_space(m), dt, hold), inputs);
}

Eigen::MatrixXd simulate(const Model& model, const Eigen::VectorXd& p, const Eigen::MatrixXd& inputs, double dt,
                         InputHold hold) {
  detail::check_parameter_vector(model, p, "simulate");
  ModelMatrices m;
  model.evaluate(p, m);
  return simulate(m, inputs, dt, hold);
}

SimulationSensitivity simulate_with_sensitivity(const ModelMatrices& m, const ModelDerivatives& d,
                                                int parameter_count, const Eigen::MatrixXd& inputs, double dt,
                                                InputHold hold) {
  const StateSpace ss = state_space(m);
  const DiscreteStateSpace sys = discretize(ss, dt, hold);
  const std::vector<DiscreteStateSpace> dsys =
      discretize_derivatives(ss, state_space_derivatives(m, d, parameter_count), dt, hold);
  check_inputs(inputs, sys.Gamma0.cols(), "simulate_with_sensitivity");

  const Eigen::Index n = sys.Phi.rows(), ni = sys.Gamma0.cols(), no = sys.C.rows(), np = parameter_count;
  const Eigen::Index samples = inputs.rows();
  // Derivative matrices stacked vertically (block i belongs to p_i), so that one product gives the forcing of
  // all parameter sensitivities; its reshape to (rows x np) is a column-major Map.
  Eigen::MatrixXd dPhi(n * np, n), dGamma0(n * np, ni), dGamma1(n * np, ni), dC(no * np, n), dD(no * np, ni);
  for (Eigen::Index i = 0; i < np; ++i) {
    const DiscreteStateSpace& di = dsys[static_cast<std::size_t>(i)];
    dPhi.middleRows(i * n, n) = di.Phi;
    dGamma0.middleRows(i * n, n) = di.Gamma0;
    dGamma1.middleRows(i * n, n) = di.Gamma1;
    dC.middleRows(i * no, no) = di.C;
    dD.middleRows(i * no, no) = di.D;
  }

  const Eigen::MatrixXd U = inputs.transpose();
  const bool first_order = hold == InputHold::FirstOrder;
  Eigen::MatrixXd Y(no, samples), dY(no * np, samples);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), next(n), forcing(n * np), output_forcing(no * np);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, np), next_S(n, np);
  for (Eigen::Index k = 0; k < samples; ++k) {
    Y.col(k).noalias() = sys.C * x;
    Y.col(k).noalias() += sys.D * U.col(k);
    output_forcing.noalias() = dC * x;
    output_forcing.noalias() += dD * U.col(k);
    Eigen::Map<Eigen::MatrixXd> dy_k(dY.col(k).data(), no, np);
    dy_k.noalias() = sys.C * S;
    dy_k += Eigen::Map<const Eigen::MatrixXd>(output_forcing.data(), no, np);
    if (k + 1 == samples) break;

    forcing.noalias() = dPhi * x;
    forcing.noalias() += dGamma0 * U.col(k);
    if (first_order) forcing.noalias() += dGamma1 * U.col(k + 1);
    next_S.noalias() = sys.Phi * S;
    next_S += Eigen::Map<const Eigen::MatrixXd>(forcing.data(), n, np);
    S.swap(next_S);

    next.noalias() = sys.Phi * x;
    next.noalias() += sys.Gamma0 * U.col(k);
    if (first_order) next.noalias() += sys.Gamma1 * U.col(k + 1);
    x.swap(next);
  }

  SimulationSensitivity result;
  result.outputs = Y.transpose();
  result.doutputs.reserve(static_cast<std::size_t>(np));
  for (Eigen::Index i = 0; i < np; ++i) result.doutputs.push_back(dY.middleRows(i * no, no).transpose());
  return result;
}

SimulationSensitivity simulate_with_sensitivity(const Model& model, const Eigen::VectorXd& p,
                                                const Eigen::MatrixXd& inputs, double dt, InputHold hold) {
  detail::check_parameter_vector(model, p, "simulate_with_sensitivity");
  ModelMatrices m;
  ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  return simulate_with_sensitivity(m, d, static_cast<int>(p.size()), inputs, dt, hold);
}

}  // namespace mbgen
