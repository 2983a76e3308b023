#pragma once
// Frames described by the compliance at the joints alone, for when no FE
// model of them exists yet: what `rigflex diagnose` fits when it tests
// frame flexibility, and what a rig file may state instead of a frame model
// (effects.*_flexibility.joint_compliance, docs/compare.md).
//
// Fixed frame: the top of a frame of columns and beams, in G - each upper
// joint on its own springs along x, y and z (m/N: a joint in the span of a
// cross beam is soft across the beam's weak axis and stiff along it), plus
// the top as a whole swaying along x and y under the sum of the joints'
// horizontal loads (m/N) and twisting about the vertical under their moment
// (rad/(N m)): the joint compliance matrix
//   C = diag(c_ix, c_iy, c_iz) + s_x X X' + s_y Y Y' + c_twist T T',
// X, Y the unit translations of all joints, T_i = z x (A_i - centroid).
// Carrying frame: the lower joints held together as one plate that moves
// against the body - along x, y and z (m/N) and rocking about x and y
// through the joints' centroid (rad/(N m)); the body's inertia loads a cage
// that way. A compliance of zero is a rigid direction (realized 1000x
// stiffer than the largest given term, see joint_compliance.cpp).
//
// The joints carry a small mass (1e-3 of the suspended mass shared by the
// joints) so that the frames' coordinates have inertia; its local modes lie
// far above the swing band and are damped at 2 %.
#include <vector>

#include "rig/effect.hpp"

namespace rigflex::rig {

struct FixedJointCompliance {
  std::vector<Vec3> joints;      // m/N along x, y, z, per upper joint
  Eigen::Vector2d sway = Eigen::Vector2d::Zero();  // m/N, the top as a whole along x, y
  double twist = 0;              // rad/(N m), the top as a whole
};
struct CarryingJointCompliance {
  Vec3 translation = Vec3::Zero();            // m/N along x, y, z (frame c)
  Eigen::Vector2d rocking = Eigen::Vector2d::Zero();  // rad/(N m) about x, y
};

// std::invalid_argument for negative or non-finite compliances, or all zero.
FixedFrameModel joint_compliance_fixed_frame(const RigGeometry& g, double suspended_mass,
                                             const FixedJointCompliance& c);
CarryingFrameModel joint_compliance_carrying_frame(const RigGeometry& g, double suspended_mass,
                                                   const CarryingJointCompliance& c);

}  // namespace rigflex::rig
