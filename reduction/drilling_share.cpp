#include "reduction/drilling_share.hpp"

#include <array>
#include <unordered_map>
#include <unordered_set>

namespace rigflex::reduction {

namespace {

// Each shell node's mean normal: the sum of its shells' corner-diagonal
// normals (the element frames' e3, fe/shell_common.hpp), normalized.
std::unordered_map<fe::NodeId, fe::Vec3> shell_node_normals(const fe::Model& model) {
  std::unordered_map<fe::NodeId, fe::Vec3> n;
  for (const fe::ShellElement& s : model.shells) {
    if (s.nodes.size() < 4) continue;
    const fe::Vec3 d1 = model.position(s.nodes[2]) - model.position(s.nodes[0]);
    const fe::Vec3 d2 = model.position(s.nodes[3]) - model.position(s.nodes[1]);
    const fe::Vec3 e3 = d1.cross(d2).normalized();
    // Opposite numbering on neighbours flips e3: orient along the first one seen.
    for (fe::NodeId id : s.nodes) {
      auto [it, fresh] = n.try_emplace(id, fe::Vec3::Zero());
      it->second += (!fresh && it->second.dot(e3) < 0) ? -e3 : e3;
    }
  }
  for (auto& [id, v] : n) {
    const double norm = v.norm();
    v = norm > 0 ? fe::Vec3(v / norm) : fe::Vec3::Zero();
  }
  // A rigid coupling's reference that hangs on one shell node and carries
  // nothing stiff itself turns with that node's rotations, drilling
  // included: a mass on it (a block hung on a single node) makes a drilling
  // mode too, its kinetic energy in the reference's rotation.
  std::unordered_set<fe::NodeId> stiff;
  for (const fe::BeamElement& b : model.beams) stiff.insert(b.nodes.begin(), b.nodes.end());
  for (const fe::SolidElement& e : model.solids) stiff.insert(e.nodes.begin(), e.nodes.end());
  for (const fe::Spring& k : model.springs) {
    stiff.insert(k.node);
    if (k.other) stiff.insert(*k.other);
  }
  for (const fe::RigidCoupling& c : model.couplings) {
    if (c.dependents.size() != 1 || !(c.dofs[3] && c.dofs[4] && c.dofs[5])) continue;
    const auto it = n.find(c.dependents.front());
    if (it != n.end() && !n.count(c.reference) && !stiff.count(c.reference)) n.emplace(c.reference, it->second);
  }
  return n;
}

}  // namespace

Eigen::VectorXd shell_drilling_share(const fe::Model& model, const fe::DofMap& dofs, const fe::SpMat& M,
                                     const Eigen::MatrixXd& vectors) {
  Eigen::VectorXd share = Eigen::VectorXd::Zero(vectors.cols());
  if (model.shells.empty()) return share;
  const auto normals = shell_node_normals(model);
  // The free columns of each shell node's three rotations (-1: not free).
  std::unordered_map<fe::NodeId, std::array<Eigen::Index, 3>> rotation;
  for (Eigen::Index c = 0; c < dofs.free_count(); ++c) {
    const int d = dofs.local[static_cast<size_t>(c)];
    if (d < 3 || !normals.count(dofs.node[static_cast<size_t>(c)])) continue;
    auto [it, fresh] = rotation.try_emplace(dofs.node[static_cast<size_t>(c)], std::array<Eigen::Index, 3>{-1, -1, -1});
    it->second[static_cast<size_t>(d - 3)] = c;
  }
  for (Eigen::Index i = 0; i < vectors.cols(); ++i) {
    const Eigen::VectorXd phi = vectors.col(i);
    Eigen::VectorXd v = Eigen::VectorXd::Zero(phi.size());
    for (const auto& [id, cols] : rotation) {
      fe::Vec3 theta = fe::Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        if (cols[static_cast<size_t>(k)] >= 0) theta(k) = phi(cols[static_cast<size_t>(k)]);
      }
      const fe::Vec3& n = normals.at(id);
      const fe::Vec3 drill = theta.dot(n) * n;
      for (int k = 0; k < 3; ++k) {
        if (cols[static_cast<size_t>(k)] >= 0) v(cols[static_cast<size_t>(k)]) = drill(k);
      }
    }
    const double mi = phi.dot(M * phi);
    share(i) = mi > 0 ? v.dot(M * v) / mi : 0.0;
  }
  return share;
}

}  // namespace rigflex::reduction
