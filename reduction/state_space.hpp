#pragma once
// First-order (state-space) form of a reduced second-order model.
#include <Eigen/Core>

#include "reduction/reduced_model.hpp"

namespace rigflex::reduction {

// M z'' + C z' + K z = E u, E = [I; 0] (u: forces at the first
// `interface_dofs` coordinates), as x' = A x + B u, y = C x + D u with
// x = [z; z'], y = [z_b; z_b'] (interface displacements and velocities):
//   A = [0, I; -M^-1 K, -M^-1 C],  B = [0; M^-1 E],
//   C = [E', 0; 0, E'],            D = 0.
// Throws std::invalid_argument if M is not positive definite or the sizes
// disagree.
StateSpace state_space_form(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                            Eigen::Index interface_dofs);

}  // namespace rigflex::reduction
