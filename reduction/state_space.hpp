#pragma once
// First-order (state-space) form of a reduced second-order model.
#include <Eigen/Core>

#include "reduction/reduced_model.hpp"

namespace rigflex::reduction {

// M z'' + C z' + K z = E u, E = [I; 0] (u: forces at the first
// `interface_dofs` coordinates), as x' = A x + B u, y = C x + D u with
// y = [z_b; z_b'] (interface displacements and velocities).
//
// Without `rigid` (a held frame) the state is physical, x = [z; z']:
//   A = [0, I; -M^-1 K, -M^-1 C],  B = [0; M^-1 E],
//   C = [E', 0; 0, E'],            D = 0,  T = I.
//
// With `rigid` (n x r, the frame's rigid motions in z, K rigid ~ 0 and
// C rigid ~ 0) the state is modal, z = T xi, x = [xi; xi']: T's first r
// columns are the rigid motions made M-orthonormal, the others the elastic
// modes of K projected onto their M-orthogonal complement, so
//   A = [0, I; -diag(0, w^2), -T' C T],  B = [0; T' E],
//   C = [E' T, 0; 0, E' T],              D = 0,
// with the rigid rows and columns of diag(0, w^2) and T' C T exactly zero.
// The physical form of a free frame carries K's round-off on its rigid
// motions (A then has eigenvalues of order sqrt(eps) w, some with a positive
// real part); this one has exactly 2r zero eigenvalues, the same inputs and
// outputs, and the same transfer function to the round-off of K rigid.
// Throws std::invalid_argument if M is not positive definite, the sizes
// disagree or `rigid` has dependent columns.
StateSpace state_space_form(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                            Eigen::Index interface_dofs, const Eigen::MatrixXd& rigid = Eigen::MatrixXd());

}  // namespace rigflex::reduction
