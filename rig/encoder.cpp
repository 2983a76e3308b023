#include "rig/encoder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rigflex::rig {

Eigen::Matrix3d rotation_about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::Vector3d second_axis(const Eigen::Vector3d& a) { return Eigen::Vector3d::UnitZ().cross(a); }

Eigen::Vector3d rod_direction(const Eigen::Vector3d& a, const EncoderAngles& angles) {
  return rotation_about(a, angles.alpha) * rotation_about(second_axis(a), angles.beta) *
         Eigen::Vector3d(0.0, 0.0, -1.0);
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
