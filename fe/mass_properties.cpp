#include "fe/mass_properties.hpp"

#include "fe/assembly.hpp"
#include "fe/shell_centres.hpp"

namespace rigflex::fe {

Eigen::Matrix<double, 6, 6> rigid_motion_at(const Vec3& x) {
  Eigen::Matrix<double, 6, 6> b = Eigen::Matrix<double, 6, 6>::Identity();
  // u = t + theta x position
  b(0, 4) = x.z();
  b(0, 5) = -x.y();
  b(1, 3) = -x.z();
  b(1, 5) = x.x();
  b(2, 3) = x.y();
  b(2, 4) = -x.x();
  return b;
}

Eigen::MatrixXd rigid_body_modes(const Model& model, const Vec3& about) {
  const auto n = static_cast<Eigen::Index>(model.nodes.size());
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(6 * n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    phi.block<6, 6>(6 * i, 0) = rigid_motion_at(model.nodes[static_cast<size_t>(i)].x - about);
  }
  // Element coordinates stay at zero in a rigid motion: a superelement's
  // basis reproduces rigid motions with the interface DOFs alone, a shell's
  // centre amplitudes are deformation above what its nodes interpolate.
  for (NodeId id : coordinate_nodes(model))
    phi.block<6, 6>(6 * static_cast<Eigen::Index>(model.node_index(id)), 0).setZero();
  return phi;
}

MassProperties mass_properties_from_rigid_mass(const Eigen::Matrix<double, 6, 6>& M_rb) {
  MassProperties p;
  p.mass = M_rb.topLeftCorner<3, 3>().trace() / 3.0;
  if (p.mass <= 0.0) return p;
  // The coupling block is m * skew(c)^T, i.e. -m * skew(c).
  const Eigen::Matrix3d S = -M_rb.topRightCorner<3, 3>() / p.mass;
  p.cog = Vec3(0.5 * (S(2, 1) - S(1, 2)), 0.5 * (S(0, 2) - S(2, 0)), 0.5 * (S(1, 0) - S(0, 1)));
  const Eigen::Matrix3d J_origin = M_rb.bottomRightCorner<3, 3>();
  const Vec3& c = p.cog;
  p.inertia = J_origin - p.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  p.inertia = 0.5 * (p.inertia + p.inertia.transpose()).eval();
  return p;
}

MassProperties mass_properties(const Model& model, const Eigen::SparseMatrix<double>& M_full) {
  const Eigen::MatrixXd phi = rigid_body_modes(model);
  const Eigen::Matrix<double, 6, 6> M_rb = phi.transpose() * (M_full * phi);
  return mass_properties_from_rigid_mass(M_rb);
}

MassProperties mass_properties(const Model& model) {
  SpMat K, M;
  assemble_full(model, K, M);
  return mass_properties(model, M);
}

}  // namespace rigflex::fe

namespace rigflex::fe {

Eigen::MatrixXd rigid_body_modes_free(const Model& model, const DofMap& dofs, const Vec3& about) {
  Eigen::MatrixXd R(dofs.free_count(), 6);
  const Eigen::MatrixXd full = rigid_body_modes(model, about);
  for (Eigen::Index j = 0; j < dofs.free_count(); ++j) {
    const auto row = 6 * static_cast<Eigen::Index>(model.node_index(dofs.node[static_cast<size_t>(j)])) +
                     dofs.local[static_cast<size_t>(j)];
    R.row(j) = full.row(row);
  }
  return R;
}

}  // namespace rigflex::fe
