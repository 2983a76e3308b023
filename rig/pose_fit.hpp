#pragma once
// The pose of the carrying frame from its joint centres: the rigid motion
// (R, r) that takes the points b_i (frame c) closest to the measured points
// B_i (G) in the least-squares sense (Kabsch / Horn). With three points the
// fit is exact when the measured triangle is congruent to the nominal one;
// a fourth point makes the residual a consistency check of the sensors.
#include <Eigen/Core>

namespace rigflex::rig {

struct PoseFit {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // frame c -> G
  Eigen::Vector3d r = Eigen::Vector3d::Zero();      // P (the origin of frame c) in G
  double rms_residual = 0.0;                        // m, sqrt(mean |r + R b_i - B_i|^2)
};

// Up to four points (the rig's 3 or 4 joints) without heap allocation.
using JointPoints = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 4>;

// body: 3 x n points in frame c; world: 3 x n points in G; 3 <= n <= 4, the
// body points not collinear (std::invalid_argument otherwise).
PoseFit fit_pose(const JointPoints& body, const JointPoints& world);

}  // namespace rigflex::rig
