#include "rig/encoder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rigflex::rig {

Eigen::Matrix3d rotation_about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::Vector3d second_axis(const Eigen::Vector3d& a) { return Eigen::Vector3d::UnitZ().cross(a); }

// R(b, beta) (0, 0, -1) = -cos(beta) z - sin(beta) a (b = z x a, a horizontal),
// then R(a, alpha) turns z into cos(alpha) z - sin(alpha) b and leaves a:
// the spec's product of rotations in closed form (the identifier evaluates
// it for every sample of every rod).
Eigen::Vector3d rod_direction(const Eigen::Vector3d& a, const EncoderAngles& angles) {
  const double ca = std::cos(angles.alpha), sa = std::sin(angles.alpha);
  const double cb = std::cos(angles.beta), sb = std::sin(angles.beta);
  return cb * (sa * second_axis(a) - ca * Eigen::Vector3d::UnitZ()) - sb * a;
}

EncoderAngles encoder_angles(const Eigen::Vector3d& a, const Eigen::Vector3d& u) {
  const Eigen::Vector3d n = u.normalized();
  const Eigen::Vector3d b = second_axis(a);
  EncoderAngles out;
  out.beta = -std::asin(std::clamp(n.dot(a), -1.0, 1.0));
  out.alpha = std::atan2(n.dot(b), -n.z());
  return out;
}

}  // namespace rigflex::rig
