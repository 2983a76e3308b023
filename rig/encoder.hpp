#pragma once
// Encoder convention of shared/spec/rig-conventions.md: the unit vector along
// rod i, from the upper joint A_i towards the lower joint B_i, is
//   u = R(a, alpha) R(b, beta) (0, 0, -1),   b = z x a,
// with a the (horizontal, unit) outer joint axis and both rotations
// right-handed. Both angles are zero when the rod hangs vertically.
#include <Eigen/Core>

namespace rigflex::rig {

struct EncoderAngles {
  double alpha = 0.0;  // rad, rotation of the outer fork about a
  double beta = 0.0;   // rad, rotation of the rod about the fork's second axis
};

// Right-handed rotation about a unit axis.
Eigen::Matrix3d rotation_about(const Eigen::Vector3d& axis, double angle);

// The second joint axis at zero angles: b = z x a.
Eigen::Vector3d second_axis(const Eigen::Vector3d& a);

// Direction -> angles -> direction are inverse for |beta| < pi/2:
// u . a = -sin(beta) and (u . b, -u . z) = cos(beta) (sin(alpha), cos(alpha)).
Eigen::Vector3d rod_direction(const Eigen::Vector3d& a, const EncoderAngles& angles);
EncoderAngles encoder_angles(const Eigen::Vector3d& a, const Eigen::Vector3d& u);

}  // namespace rigflex::rig
