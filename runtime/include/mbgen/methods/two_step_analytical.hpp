// The analytical route (a) of the two-step method's step two (thesis Sec. 3.6.2, Table 3.2; docs/methods.md#two-step):
// the coefficient equations L_i(p) = L^_i solved exactly. The runtime has no computer algebra, so it hands the
// equations to an AnalyticalSolver that a caller supplies (`mbgen fit` supplies GiNaC's, compiler/elimination/) and
// judges the solutions it returns (real, within the bounds, a positive definite mass matrix) by the numbers it has.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mbgen {

// Step two's equations as the solver sees them: model coefficient = identified value.
struct CoefficientSystem {
  struct TransferFunction {
    std::string file;
    int input = 0;                                  // model input index
    std::vector<int> outputs;                       // model output indices (channel c is outputs[c])
    std::vector<std::pair<int, double>> overrides;  // the data set's `# set` values (model parameter index, value)
    int order = 0;                                  // degree of the monic denominator
  };
  struct Equation {
    std::size_t tf = 0;
    int channel = -1;           // -1: the denominator's coefficient, else numerator of outputs[channel]
    int power = 0;              // of s
    double identified = 0;      // L^_i
    double model_at_prior = 0;  // L_i at `values`: lets the solver check that its coefficients are the runtime's
  };
  std::vector<TransferFunction> tfs;
  std::vector<Equation> equations;
  std::vector<int> unknowns;  // model parameter indices to solve for
  Eigen::VectorXd values;     // every model parameter: the others are held at these values
};

// One square subsystem (as many equations as unknowns) and its exact solutions.
struct AnalyticalSubsystem {
  std::vector<int> equations;              // indices into CoefficientSystem::equations
  std::vector<std::string> closed_form;    // per unknown: "name = expression in the identified coefficients"
  std::vector<Eigen::VectorXd> solutions;  // its real solutions, full parameter vectors (the others from `values`)
  std::vector<std::vector<std::string>> exact;  // per solution, per unknown: the exact value (a rational, or radicals)
  std::string failure;                     // non-empty: it has no closed form (or no real solution), and why
};

struct AnalyticalSolution {
  std::string unavailable;                    // non-empty: the route does not apply to this system at all, and why
  std::vector<std::string> coefficient_names;  // per equation: its symbol in the closed forms
  std::string subsystem_choice;               // how the square subsystems were formed
  std::vector<AnalyticalSubsystem> subsystems;
};

using AnalyticalSolver = std::function<AnalyticalSolution(const CoefficientSystem&)>;

}  // namespace mbgen
