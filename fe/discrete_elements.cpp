#include "fe/discrete_elements.hpp"

namespace rigflex::fe {

Eigen::Matrix<double, 6, 6> point_mass_matrix(const PointMass& p) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m.topLeftCorner<3, 3>() = p.mass * Eigen::Matrix3d::Identity();
  const auto& J = p.inertia;
  // With the negative-integral convention the products enter the tensor as given.
  m.bottomRightCorner<3, 3>() << J[0], J[3], J[4], J[3], J[1], J[5], J[4], J[5], J[2];
  return m;
}

Eigen::Matrix<double, 6, 6> spring_stiffness(const Spring& s, const Vec3& node_position,
                                             const Vec3& other_position) {
  Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero();
  for (int d = 0; d < 6; ++d) k(d, d) = s.stiffness[static_cast<size_t>(d)];
  if (s.axial) {
    const Vec3 dir = (s.direction ? *s.direction : Vec3(other_position - node_position)).normalized();
    k.topLeftCorner<3, 3>() += *s.axial * dir * dir.transpose();
  }
  return k;
}

}  // namespace rigflex::fe
