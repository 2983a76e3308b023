#include "fe/distributing_coupling.hpp"

#include <Eigen/Eigenvalues>

#include "fe/skew.hpp"

namespace rigflex::fe {

std::optional<Eigen::MatrixXd> distributing_link(const Vec3& reference, const std::vector<Vec3>& nodes,
                                                 const std::vector<double>& weights) {
  const size_t n = nodes.size();
  auto w = [&](size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  double W = 0;
  Vec3 c = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) {
    W += w(i);
    c += w(i) * nodes[i];
  }
  if (n < 3 || !(W > 0)) return std::nullopt;
  c /= W;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  double size = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 r = nodes[i] - c;
    S += w(i) * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    size = std::max(size, r.norm());
  }
  // Collinear nodes leave S singular about their line; relative to the
  // spread of the nodes, 1e-10 is far below any real face and far above
  // rounding.
  const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();
  if (!(eig(0) > 1e-10 * eig(2)) || !(size > 0)) return std::nullopt;
  const Eigen::Matrix3d Sinv = S.inverse();
  const Eigen::Matrix3d lever = skew(reference - c);
  Eigen::MatrixXd G(6, 3 * static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d rot = w(i) * Sinv * skew(nodes[i] - c);  // theta from u_i
    const auto col = 3 * static_cast<Eigen::Index>(i);
    G.block<3, 3>(3, col) = rot;
    G.block<3, 3>(0, col) = w(i) / W * Eigen::Matrix3d::Identity() - lever * rot;
  }
  return G;
}

}  // namespace rigflex::fe
