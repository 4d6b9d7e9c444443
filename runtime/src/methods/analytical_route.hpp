// The two-step method's route (a), the runtime's part: the coefficient equations handed to the caller's exact solver
// (two_step_analytical.hpp), its solutions judged by the numbers. Internal header.
//
// Every real solution of every square subsystem is checked: it must satisfy its own equations numerically (a
// solver whose coefficients are not the runtime's is caught here), lie within the parameters' bounds and give a
// positive definite mass matrix. Of a subsystem's admissible solutions the one nearest the minimisation's estimate
// is its candidate (several roots: as Newton's are chosen). The equations left out are the checks: their normalised
// mismatch at the solution. Of the subsystems' candidates, with step one's coefficient covariance (FRFs), the one
// with the smallest predicted error wins: the RMS relative parameter error that the identified coefficients' errors
// cause through the subsystem's exact solution, sqrt(trace(G S G^T) / n), G = (J_S diag(p))^-1 the sensitivity of
// the relative parameters to the normalised coefficients of the subsystem S, S their normalised covariance. Without
// one (records), the one whose checks are met best (smallest RMS mismatch): taking every coefficient as equally
// uncertain instead, as the thesis's normalisation does, picks subsystems that trust the poorly identified
// antiresonance damping and is several times worse on mdof2's records.
#pragma once

#include "coefficient_problem.hpp"
#include "mbgen/methods/two_step_analytical.hpp"
#include "mbgen/model.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mbgen::methods {

struct AnalyticalOutcome {
  bool solved = false;
  std::string reason;         // why not, when !solved
  Eigen::VectorXd values;     // the chosen solution (full parameter vector)
  std::vector<int> equations; // the chosen subsystem (indices into the problem's targets)
  Eigen::MatrixXd covariance; // of the free parameters, from step one's covariance; empty where there is none
  nlohmann::json details;     // method_details.two_step.step_two.analytical
};

// Within the bounds of `free` and a model that evaluates with a positive definite mass matrix.
bool admissible(const Model& model, const Eigen::VectorXd& values, const std::vector<int>& free);

AnalyticalOutcome analytical_route(const Model& model, const std::vector<StepOneTf>& tfs, const std::vector<int>& free,
                                   const Eigen::VectorXd& prior, const Eigen::VectorXd& minimum,
                                   const AnalyticalSolver& solver);

}  // namespace mbgen::methods
