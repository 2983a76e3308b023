#pragma once
// Building blocks of the checks that ship with every reduction
// (ReductionChecks): rigid motions of the interface, MAC, isostatic holding
// of a floating frame, static interface flexibility.
#include <Eigen/Core>
#include <vector>

#include "reduction/reduced_model.hpp"
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::reduction {

// Rigid-body motions in reduced coordinates (columns: translations X Y Z,
// rotations about the global X Y Z axes through the origin; modal
// coordinates zero). `coordinates` >= interface DOFs.
Eigen::MatrixXd interface_rigid_motions(const std::vector<InterfaceNode>& nodes,
                                        const std::vector<InterfaceDof>& dofs, Eigen::Index coordinates);

// MAC_ij = (a_i' b_j)^2 / ((a_i' a_i) (b_j' b_j)) for the columns of A and B.
Eigen::MatrixXd mac_matrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

// The fraction of a's squared norm that lies in the span of the columns of
// B: ||P_B a||^2 / ||a||^2. Equals the MAC for one column and, unlike it,
// does not depend on which basis a solver picked for a repeated eigenvalue.
double subspace_mac(const Eigen::VectorXd& a, const Eigen::MatrixXd& B);

// Rows of `rigid` (one per interface DOF) that hold the six rigid motions
// statically determinately: chosen greedily in order, each raising the rank.
// Fewer than six when the interface cannot hold the body (collinear nodes).
std::vector<Eigen::Index> isostatic_rows(const Eigen::MatrixXd& rigid);

// Interface flexibility of the full model: G = (K^-1)_bb over `boundary`
// (free-DOF indices), with the DOFs `held` additionally fixed (their rows
// and columns removed). Factorizes K without `held` once; throws
// std::runtime_error if that is not positive definite.
Eigen::MatrixXd full_interface_flexibility(const linalg::SpMat& K, const std::vector<Eigen::Index>& boundary,
                                           const std::vector<Eigen::Index>& held);
// The same from a dense reduced stiffness; `boundary` and `held` index its coordinates.
Eigen::MatrixXd reduced_interface_flexibility(const Eigen::MatrixXd& K, const std::vector<Eigen::Index>& boundary,
                                              const std::vector<Eigen::Index>& held);

}  // namespace rigflex::reduction
