#pragma once
// The cross-product matrix: skew(a) b = a x b.
#include <Eigen/Core>

namespace rigflex::fe {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

}  // namespace rigflex::fe
