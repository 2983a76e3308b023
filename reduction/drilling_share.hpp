#pragma once
// How much of each mode's kinetic energy lies in the shells' drilling
// rotations: the rotation of a shell node about its mean normal is no
// physical motion of a shell (its stiffness is a stabilization term), so a
// mode that lives there is spurious (reduction/modal_summary.hpp).
#include <Eigen/Dense>

#include "fe/assembly.hpp"
#include "fe/model.hpp"

namespace rigflex::reduction {

// Per column of `vectors` (free DOFs of `dofs`): v' M v / phi' M phi, with v
// the mode's rotation at each shell node projected onto the node's mean
// normal (the average of its shells' normals) - and at the reference of a
// rigid coupling to a single shell node, onto that node's normal, where
// nothing stiff is attached to the reference - zero elsewhere. Zeros
// without shells.
Eigen::VectorXd shell_drilling_share(const fe::Model& model, const fe::DofMap& dofs, const fe::SpMat& M,
                                     const Eigen::MatrixXd& vectors);

}  // namespace rigflex::reduction
