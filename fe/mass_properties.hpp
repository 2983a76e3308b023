#pragma once
// Mass, centre of gravity and inertia tensor of a model, from its mass matrix.
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "fe/model.hpp"

namespace rigflex::fe {

struct MassProperties {
  double mass = 0.0;
  Vec3 cog = Vec3::Zero();
  // About the CoG, axes parallel to global; negative-integral products, so
  // the matrix is the inertia tensor [[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], ...].
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

// The six DOFs of a point at x (relative to the centre of rotation) under
// the six unit rigid motions: translations X Y Z, rotations about X Y Z
// (u = t + theta x x).
Eigen::Matrix<double, 6, 6> rigid_motion_at(const Vec3& x);

// 6N x 6 rigid-body modes (translations, then rotations about `about`).
Eigen::MatrixXd rigid_body_modes(const Model& model, const Vec3& about = Vec3::Zero());

// From the full mass matrix (assemble_full): M_rb = Phi' M Phi, then the
// inertia is moved from the origin to the CoG.
MassProperties mass_properties(const Model& model, const Eigen::SparseMatrix<double>& M_full);
MassProperties mass_properties(const Model& model);

// The same transfer for a 6x6 rigid-body mass matrix about the origin.
MassProperties mass_properties_from_rigid_mass(const Eigen::Matrix<double, 6, 6>& M_rb);

}  // namespace rigflex::fe

namespace rigflex::fe {
struct DofMap;
// Rigid-body modes on the free DOFs of an assembled system (rotations about
// `about`): the influence vectors for participation factors.
Eigen::MatrixXd rigid_body_modes_free(const Model& model, const DofMap& dofs, const Vec3& about);
}  // namespace rigflex::fe
