#include "rig/joint_compliance.hpp"

#include <algorithm>
#include <cmath>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <stdexcept>

#include "rig/skew.hpp"

namespace rigflex::rig {
namespace {

constexpr double kZeta = 0.02;
constexpr double kJointMassShare = 1e-3;

// Stiffnesses 1/c, a zero compliance 1000x stiffer than the largest given one.
Eigen::VectorXd stiffness_of(const Eigen::VectorXd& c, const Eigen::VectorXd& scale, const std::string& what) {
  double largest = 0;
  for (Eigen::Index i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c(i)) || c(i) < 0) throw std::invalid_argument(what + ": compliances must be >= 0 and finite");
    largest = std::max(largest, c(i) / scale(i));
  }
  if (largest <= 0) throw std::invalid_argument(what + ": at least one compliance must be positive");
  Eigen::VectorXd k(c.size());
  for (Eigen::Index i = 0; i < c.size(); ++i) k(i) = 1.0 / std::max(c(i), 1e-3 * largest * scale(i));
  return k;
}

}  // namespace

FixedFrameModel joint_compliance_fixed_frame(const RigGeometry& g, double suspended_mass,
                                             const FixedJointCompliance& c) {
  const int n = g.rod_count();
  if (static_cast<int>(c.joints.size()) != n) {
    throw std::invalid_argument("fixed_frame_flexibility.joint_compliance.joints: needs one [x, y, z] per rod (" +
                                std::to_string(n) + ")");
  }
  Vec3 centroid = Vec3::Zero();
  for (const auto& r : g.rods) centroid += r.upper / n;
  double rho2 = 0;
  for (const auto& r : g.rods) rho2 += (r.upper - centroid).head<2>().squaredNorm() / n;
  if (rho2 <= 0) throw std::invalid_argument("fixed_frame_flexibility.joint_compliance: the joints coincide");
  Eigen::VectorXd all(3 * n + 3), scale = Eigen::VectorXd::Ones(3 * n + 3);
  for (int i = 0; i < n; ++i) all.segment<3>(3 * i) = c.joints[static_cast<size_t>(i)];
  all.segment<2>(3 * n) = c.sway;
  all(3 * n + 2) = c.twist;
  scale(3 * n + 2) = 1.0 / rho2;
  // The joints' own terms keep C positive definite: a zero one is 1000x
  // stiffer than the largest term.
  const Eigen::VectorXd k = stiffness_of(all, scale, "fixed_frame_flexibility.joint_compliance");
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::VectorXd X = Eigen::VectorXd::Zero(3 * n), Y = X, T = X;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) C(3 * i + d, 3 * i + d) = 1.0 / k(3 * i + d);
    X(3 * i) = Y(3 * i + 1) = 1.0;
    T.segment<3>(3 * i) = Vec3::UnitZ().cross(g.rods[static_cast<size_t>(i)].upper - centroid);
  }
  C += c.sway(0) * X * X.transpose() + c.sway(1) * Y * Y.transpose() + c.twist * T * T.transpose();
  const double m = kJointMassShare * suspended_mass / n;
  FixedFrameModel f;
  f.K = C.inverse();
  f.K = 0.5 * (f.K + f.K.transpose());
  f.M = m * Eigen::MatrixXd::Identity(3 * n, 3 * n);
  // Modal damping at 2 % (M is a multiple of the identity, so K's eigenvectors are the modes).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(f.K);
  f.C = es.eigenvectors() * (2.0 * kZeta * (es.eigenvalues().cwiseMax(0.0) * m).cwiseSqrt()).asDiagonal() *
        es.eigenvectors().transpose();
  for (int i = 0; i < n; ++i) f.joint_row.push_back(3 * i);
  f.source = "joint compliance";
  return f;
}

CarryingFrameModel joint_compliance_carrying_frame(const RigGeometry& g, double suspended_mass,
                                                   const CarryingJointCompliance& c) {
  const int n = g.rod_count();
  Vec3 centroid = Vec3::Zero();
  for (const auto& r : g.rods) centroid += r.lower;
  centroid /= n;
  double rho2 = 0;
  for (const auto& r : g.rods) rho2 += (r.lower - centroid).squaredNorm();
  rho2 /= n;
  if (rho2 <= 0) throw std::invalid_argument("carrying_frame_flexibility.joint_compliance: the joints coincide");
  Eigen::Matrix<double, 5, 1> all, scale;
  all << c.translation, c.rocking;
  scale << 1, 1, 1, 1.0 / rho2, 1.0 / rho2;  // rocking compared with translation over the joints' radius
  const Eigen::VectorXd k = stiffness_of(all, scale, "carrying_frame_flexibility.joint_compliance");
  const double m = kJointMassShare * suspended_mass;
  const double I = m * rho2;
  // Plate coordinates q = (t, theta): joint displacement d_i = t + theta x rho_i;
  // yaw held by the horizontal stiffnesses acting at the joints' radius.
  Eigen::Matrix<double, 6, 1> kq, mq;
  kq << k(0), k(1), k(2), k(3), k(4), 0.5 * (k(0) + k(1)) * rho2 * n;
  mq << m, m, m, I, I, I;
  CarryingFrameModel f;
  f.psi.resize(3 * n, 6);
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix<double, 3, 6> T;
    T << Eigen::Matrix3d::Identity(), -skew(g.rods[static_cast<size_t>(i)].lower - centroid);
    f.psi.middleRows(3 * i, 3) = T * mq.cwiseSqrt().cwiseInverse().asDiagonal();
  }
  f.omega2 = kq.cwiseQuotient(mq);
  f.damping = (2.0 * kZeta * f.omega2.cwiseSqrt()).asDiagonal();
  f.source = "joint compliance";
  return f;
}

}  // namespace rigflex::rig
