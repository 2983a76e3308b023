#include "rig/pose_fit.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

namespace rigflex::rig {

PoseFit fit_pose(const JointPoints& body, const JointPoints& world) {
  const Eigen::Index n = body.cols();
  if (n < 3 || n > 4 || world.cols() != n) {
    throw std::invalid_argument("fit_pose: needs the same 3 or 4 points in both frames");
  }
  const Eigen::Vector3d cb = body.rowwise().mean();
  const Eigen::Vector3d cw = world.rowwise().mean();
  const JointPoints b = body.colwise() - cb;
  const JointPoints w = world.colwise() - cw;
  // Collinear body points leave the rotation about their line free: some
  // pair of centred points must span a plane.
  double area = 0, span = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    span = std::max(span, b.col(i).squaredNorm());
    for (Eigen::Index j = i + 1; j < n; ++j) area = std::max(area, b.col(i).cross(b.col(j)).norm());
  }
  if (!(area > 1e-9 * span)) throw std::invalid_argument("fit_pose: the body points are collinear");
  const Eigen::Matrix3d H = w * b.transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // The sign fix keeps R a rotation when the points are coplanar (the
  // three-rod rig) or the data noisy: the reflection is never the answer.
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  PoseFit fit;
  fit.R = svd.matrixU() * D * svd.matrixV().transpose();
  fit.r = cw - fit.R * cb;
  fit.rms_residual = std::sqrt((fit.R * b - w).squaredNorm() / static_cast<double>(n));
  return fit;
}

}  // namespace rigflex::rig
