// Internal: size checks and the mass-matrix factorisation shared by the dynamics algorithms.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include <string>

namespace mbgen::detail {

void require_square(const Eigen::MatrixXd& X, Eigen::Index n, const char* name, const char* where);
void require_shape(const Eigen::MatrixXd& X, Eigen::Index rows, Eigen::Index cols, const char* name,
                   const char* where);

// LU factorisation of M; throws DynamicsError naming `where` if M is singular (reciprocal condition number below
// ~n * machine epsilon), e.g. a coordinate that carries no mass.
Eigen::PartialPivLU<Eigen::MatrixXd> factor_mass(const Eigen::MatrixXd& M, const char* where);

}  // namespace mbgen::detail
