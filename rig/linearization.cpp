#include "rig/linearization.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rigflex::rig {

const char* to_string(RigModeKind k) {
  switch (k) {
    case RigModeKind::swing: return "swing";
    case RigModeKind::deformation: return "deformation";
    case RigModeKind::rod_constraint: return "rod constraint";
  }
  return "?";
}

Linearization linearize(const RigSystem& rig) {
  Linearization lin;
  lin.equilibrium = static_equilibrium(rig);
  if (!lin.equilibrium.converged) throw NoEquilibrium(lin.equilibrium.message);
  const Eigen::MatrixXd K = tangent_stiffness(rig, lin.equilibrium.configuration);
  lin.asymmetry = (K - K.transpose()).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
  lin.K = 0.5 * (K + K.transpose());
  lin.M = rig.mass_matrix();
  const int n = rig.coordinate_count();
  // A shift below the lowest swing frequency of any real rig (0.01 Hz) keeps
  // K - sigma M positive definite.
  const double shift = -std::pow(2.0 * std::numbers::pi * 0.01, 2);
  lin.eigen = linalg::solve_dense(lin.K, lin.M, n, shift);
  linalg::check_eigenpairs(lin.K.sparseView(), lin.M.sparseView(), lin.eigen);
  const Eigen::VectorXd f = lin.eigen.frequencies_hz();
  for (Eigen::Index j = 0; j < lin.eigen.eigenvalues.size(); ++j) {
    RigMode m;
    m.frequency_hz = f(j);
    m.shape = lin.eigen.vectors.col(j);
    m.strain = rig.incremental_strain_energy(lin.equilibrium.configuration, m.shape);
    const double potential = 0.5 * std::max(lin.eigen.eigenvalues(j), 0.0);
    m.elastic_fraction = potential > 0 ? m.strain.total() / potential : 0.0;
    m.body_fraction = m.shape.head<6>().dot(lin.M.topLeftCorner<6, 6>() * m.shape.head<6>());
    if (m.elastic_fraction < 0.5 && m.body_fraction >= 0.5) {
      m.kind = RigModeKind::swing;
    } else if (rig.rods_rigid() && m.strain.rods > 0.5 * m.strain.total()) {
      m.kind = RigModeKind::rod_constraint;
    } else {
      m.kind = RigModeKind::deformation;
    }
    lin.modes.push_back(m);
  }
  return lin;
}

}  // namespace rigflex::rig
