#include "reduction/reduction_checks.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

#include "fe/mass_properties.hpp"

namespace rigflex::reduction {
namespace {

// Positions of `wanted` within the DOFs that remain after removing `held`;
// -1 for none. Both index the same 0..n-1 set.
std::vector<Eigen::Index> remaining_index(Eigen::Index n, const std::vector<Eigen::Index>& held) {
  std::vector<Eigen::Index> map(static_cast<size_t>(n), 0);
  for (Eigen::Index h : held) map[static_cast<size_t>(h)] = -1;
  Eigen::Index next = 0;
  for (auto& m : map) m = (m < 0) ? -1 : next++;
  return map;
}

// Unit loads at the remaining boundary DOFs, solved by `solve`; the
// displacements there form the (symmetrized) flexibility matrix.
template <class Solve>
Eigen::MatrixXd unit_load_flexibility(Eigen::Index m, const std::vector<Eigen::Index>& map,
                                      const std::vector<Eigen::Index>& boundary, Solve solve) {
  std::vector<Eigen::Index> loaded;
  for (Eigen::Index b : boundary)
    if (map[static_cast<size_t>(b)] >= 0) loaded.push_back(map[static_cast<size_t>(b)]);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(m, static_cast<Eigen::Index>(loaded.size()));
  for (size_t k = 0; k < loaded.size(); ++k) E(loaded[k], static_cast<Eigen::Index>(k)) = 1.0;
  const Eigen::MatrixXd X = solve(E);
  Eigen::MatrixXd G(E.cols(), E.cols());
  for (size_t k = 0; k < loaded.size(); ++k) G.row(static_cast<Eigen::Index>(k)) = X.row(loaded[k]);
  return 0.5 * (G + G.transpose());
}

}  // namespace

Eigen::MatrixXd interface_rigid_motions(const std::vector<InterfaceNode>& nodes,
                                        const std::vector<InterfaceDof>& dofs, Eigen::Index coordinates) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(coordinates, 6);
  for (size_t r = 0; r < dofs.size(); ++r) {
    const auto node = std::find_if(nodes.begin(), nodes.end(), [&](const InterfaceNode& n) { return n.id == dofs[r].node; });
    if (node == nodes.end()) throw std::invalid_argument("interface DOF of a node that is not an interface node");
    R.row(static_cast<Eigen::Index>(r)) = fe::rigid_motion_at(node->position).row(dofs[r].local);
  }
  return R;
}

Eigen::MatrixXd mac_matrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::MatrixXd AB = A.transpose() * B;
  const Eigen::VectorXd a2 = A.colwise().squaredNorm();
  const Eigen::VectorXd b2 = B.colwise().squaredNorm();
  Eigen::MatrixXd mac(A.cols(), B.cols());
  for (Eigen::Index i = 0; i < A.cols(); ++i)
    for (Eigen::Index j = 0; j < B.cols(); ++j) {
      const double den = a2(i) * b2(j);
      mac(i, j) = den > 0 ? AB(i, j) * AB(i, j) / den : 0.0;
    }
  return mac;
}

double subspace_mac(const Eigen::VectorXd& a, const Eigen::MatrixXd& B) {
  const double a2 = a.squaredNorm();
  if (a2 == 0.0 || B.cols() == 0) return 0.0;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(B);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(B.rows(), B.cols());
  return std::min(1.0, (Q.transpose() * a).squaredNorm() / a2);
}

std::vector<Eigen::Index> isostatic_rows(const Eigen::MatrixXd& rigid) {
  std::vector<Eigen::Index> rows;
  Eigen::MatrixXd picked(0, rigid.cols());
  Eigen::Index rank = 0;
  const double scale = std::max(1.0, rigid.cwiseAbs().maxCoeff());
  for (Eigen::Index r = 0; r < rigid.rows() && rank < rigid.cols(); ++r) {
    Eigen::MatrixXd trial(picked.rows() + 1, rigid.cols());
    trial << picked, rigid.row(r);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(trial);
    qr.setThreshold(1e-8 / scale);
    if (qr.rank() > rank) {
      picked = trial;
      rank = qr.rank();
      rows.push_back(r);
    }
  }
  return rows;
}

Eigen::MatrixXd full_interface_flexibility(const linalg::SpMat& K, const std::vector<Eigen::Index>& boundary,
                                           const std::vector<Eigen::Index>& held) {
  const auto map = remaining_index(K.rows(), held);
  const Eigen::Index m = K.rows() - static_cast<Eigen::Index>(held.size());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(K.nonZeros()));
  for (Eigen::Index j = 0; j < K.outerSize(); ++j) {
    if (map[static_cast<size_t>(j)] < 0) continue;
    for (linalg::SpMat::InnerIterator it(K, j); it; ++it) {
      const Eigen::Index r = map[static_cast<size_t>(it.row())];
      if (r >= 0) t.emplace_back(r, map[static_cast<size_t>(j)], it.value());
    }
  }
  linalg::SpMat Ks(m, m);
  Ks.setFromTriplets(t.begin(), t.end());
  t.clear();
  t.shrink_to_fit();
  linalg::SparseCholesky factor;
  const linalg::FactorStatus status = factor.factorize(Ks);
  if (!status.ok) throw std::runtime_error("static check: the held full stiffness is not positive definite");
  return unit_load_flexibility(m, map, boundary, [&](const Eigen::MatrixXd& E) { return factor.solve(E); });
}

Eigen::MatrixXd reduced_interface_flexibility(const Eigen::MatrixXd& K, const std::vector<Eigen::Index>& boundary,
                                              const std::vector<Eigen::Index>& held) {
  const auto map = remaining_index(K.rows(), held);
  const Eigen::Index m = K.rows() - static_cast<Eigen::Index>(held.size());
  Eigen::MatrixXd Ks(m, m);
  for (Eigen::Index j = 0; j < K.cols(); ++j)
    for (Eigen::Index i = 0; i < K.rows(); ++i)
      if (map[size_t(i)] >= 0 && map[size_t(j)] >= 0) Ks(map[size_t(i)], map[size_t(j)]) = K(i, j);
  const Eigen::LLT<Eigen::MatrixXd> llt(Ks);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("static check: the held reduced stiffness is not positive definite");
  }
  return unit_load_flexibility(m, map, boundary, [&](const Eigen::MatrixXd& E) -> Eigen::MatrixXd { return llt.solve(E); });
}

}  // namespace rigflex::reduction
