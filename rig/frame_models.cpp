#include "rig/frame_models.hpp"

#include <Eigen/Eigenvalues>
#include <limits>
#include <stdexcept>
#include <string>

namespace rigflex::rig {
namespace {

// Row of the UX DOF of the interface node nearest to `joint`; UY and UZ follow.
int joint_row(const reduction::ReducedFrame& frame, const Vec3& joint, const FrameMatching& m,
              const std::string& what) {
  double best = std::numeric_limits<double>::infinity();
  fe::NodeId id = 0;
  for (const auto& node : frame.interface_nodes) {
    const double d = (node.position + m.offset - joint).norm();
    if (d < best) best = d, id = node.id;
  }
  if (!(best <= m.tolerance)) {
    throw std::invalid_argument(what + ": no interface node of frame '" + frame.name + "' within " +
                                std::to_string(m.tolerance) + " m of the joint centre (nearest " +
                                std::to_string(best) + " m)");
  }
  int rows[3] = {-1, -1, -1};
  for (size_t r = 0; r < frame.interface_dofs.size(); ++r) {
    const auto& dof = frame.interface_dofs[r];
    if (dof.node == id && dof.local < 3) rows[dof.local] = static_cast<int>(r);
  }
  if (rows[0] < 0 || rows[1] != rows[0] + 1 || rows[2] != rows[0] + 2) {
    throw std::invalid_argument(what + ": node " + std::to_string(id) + " of frame '" + frame.name +
                                "' does not retain its three translations");
  }
  return rows[0];
}

}  // namespace

FixedFrameModel fixed_frame_model(const reduction::ReducedFrame& frame, const RigGeometry& geometry,
                                  const FrameMatching& matching) {
  if (frame.support != reduction::FrameSupport::grounded) {
    throw std::invalid_argument("fixed frame '" + frame.name + "' must be reduced grounded (support " +
                                reduction::to_string(frame.support) + ")");
  }
  FixedFrameModel f;
  f.K = frame.K;
  f.M = frame.M;
  f.C = frame.C.size() ? frame.C : Eigen::MatrixXd::Zero(frame.K.rows(), frame.K.cols());
  f.source = frame.name;
  for (int i = 0; i < geometry.rod_count(); ++i) {
    f.joint_row.push_back(joint_row(frame, geometry.rods[i].upper, matching,
                                    "upper joint of rod " + std::to_string(i + 1)));
  }
  Eigen::LLT<Eigen::MatrixXd> llt(f.K);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("fixed frame '" + frame.name + "': reduced stiffness is not positive definite");
  }
  return f;
}

CarryingFrameModel carrying_frame_model(const reduction::ReducedFrame& frame, const RigGeometry& geometry,
                                        const FrameMatching& matching) {
  if (frame.support != reduction::FrameSupport::free) {
    throw std::invalid_argument("carrying frame '" + frame.name + "' must be reduced free-free (support " +
                                reduction::to_string(frame.support) + ")");
  }
  const int n = geometry.rod_count();
  std::vector<int> rows;
  for (int i = 0; i < n; ++i) {
    rows.push_back(joint_row(frame, geometry.rods[i].lower, matching, "lower joint of rod " + std::to_string(i + 1)));
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(frame.K, frame.M);
  if (eig.info() != Eigen::Success) {
    throw std::invalid_argument("carrying frame '" + frame.name + "': eigen decomposition failed");
  }
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const double tiny = 1e-8 * lambda.cwiseAbs().maxCoeff();
  const int rigid = static_cast<int>((lambda.array() < tiny).count());
  if (rigid != 6) {
    throw std::invalid_argument("carrying frame '" + frame.name + "': expected 6 rigid-body modes of the free-free "
                                "reduced model, found " + std::to_string(rigid));
  }
  const Eigen::Index ne = lambda.size() - 6;
  const Eigen::MatrixXd phi = eig.eigenvectors().rightCols(ne);  // M-normalized
  CarryingFrameModel c;
  c.source = frame.name;
  c.omega2 = lambda.tail(ne);
  c.psi.resize(3 * n, ne);
  for (int i = 0; i < n; ++i) c.psi.middleRows(3 * i, 3) = phi.middleRows(rows[i], 3);
  const Eigen::MatrixXd C = frame.C.size() ? frame.C : Eigen::MatrixXd::Zero(frame.K.rows(), frame.K.cols());
  c.damping = phi.transpose() * C * phi;
  return c;
}

}  // namespace rigflex::rig
