#include "fe/shell_point_mass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "fe/discrete_elements.hpp"
#include "fe/distributing_coupling.hpp"
#include "fe/shell_common.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_detail;

using ShellsAtNode = std::unordered_map<NodeId, std::vector<const ShellElement*>>;

// Nodes where a point mass keeps its node's rotations: where something
// other than a shell stiffens, drives or holds them (a beam, a spring, a
// rigid coupling, a support of a rotation - on a symmetry plane the
// footprint's rotation is not the node's), and, to stay on the safe side,
// wherever a solid or a distributing coupling meets the node (they neither
// stiffen nor drive its rotations, so a rotary mass there can still make a
// drilling mode).
std::unordered_set<NodeId> rotation_carriers(const Model& m) {
  std::unordered_set<NodeId> s;
  for (const Support& u : m.supports)
    if (u.fixed[3] || u.fixed[4] || u.fixed[5]) s.insert(u.node);
  for (const BeamElement& b : m.beams) s.insert(b.nodes.begin(), b.nodes.end());
  for (const SolidElement& e : m.solids) s.insert(e.nodes.begin(), e.nodes.end());
  for (const Spring& k : m.springs) {
    s.insert(k.node);
    if (k.other) s.insert(*k.other);
  }
  for (const RigidCoupling& c : m.couplings) {
    s.insert(c.reference);
    s.insert(c.dependents.begin(), c.dependents.end());
  }
  for (const DistributingCoupling& c : m.distributing_couplings) {
    s.insert(c.reference);
    s.insert(c.nodes.begin(), c.nodes.end());
  }
  return s;
}

// The plane of the shells at a node: their area-weighted mean normal (each
// oriented like the first), or nothing where one of them lies more than
// kShellPlaneDegrees off it (a fold).
std::optional<Vec3> shell_plane_normal(const Model& m, const std::vector<const ShellElement*>& shells) {
  Vec3 S = Vec3::Zero();
  std::vector<Vec3> normals, x;
  for (const ShellElement* e : shells) {
    x.clear();
    for (NodeId id : e->nodes) x.push_back(m.position(id));
    const LocalFrame f = make_local_frame(x);
    Vec3 e3 = f.R.row(2).transpose();
    if (!normals.empty() && e3.dot(normals.front()) < 0.0) e3 = -e3;
    S += f.area * e3;
    normals.push_back(e3);
  }
  const Vec3 n = S.normalized();
  const double min_cos = std::cos(kShellPlaneDegrees * std::numbers::pi / 180.0);
  for (const Vec3& e3 : normals)
    if (e3.dot(n) < min_cos) return std::nullopt;
  return n;
}

// The nodes over which the mass's rotation is measured: those of the
// shells around its node, and of every shell reached from them through
// nodes within `radius` of it whose normal lies within kShellPlaneDegrees
// of n - a footprint of fixed size, so the result converges as the mesh is
// refined, where the shells around the node alone shrink with it (their
// rotational stiffness with them).
std::vector<NodeId> footprint(const Model& m, const ShellsAtNode& shells_at, NodeId node, const Vec3& n,
                              double radius) {
  const double min_cos = std::cos(kShellPlaneDegrees * std::numbers::pi / 180.0);
  const Vec3& x0 = m.position(node);
  std::set<NodeId> nodes{node};
  std::set<const ShellElement*> seen;
  std::vector<NodeId> frontier{node};
  std::vector<Vec3> x;
  while (!frontier.empty()) {
    const NodeId at = frontier.back();
    frontier.pop_back();
    for (const ShellElement* e : shells_at.at(at)) {
      if (!seen.insert(e).second) continue;
      x.clear();
      for (NodeId id : e->nodes) x.push_back(m.position(id));
      if (at != node && std::abs(make_local_frame(x).R.row(2).dot(n.transpose())) < min_cos) continue;
      for (NodeId id : e->nodes) {
        if (!nodes.insert(id).second) continue;
        if ((m.position(id) - x0).norm() <= radius && shells_at.count(id)) frontier.push_back(id);
      }
    }
  }
  return {nodes.begin(), nodes.end()};
}

// At most this many nodes measure a footprint's rotation: the mass matrix
// is dense over them (3 DOFs each), so a fine mesh under a large footprint
// is sampled evenly by distance from the node instead of taken whole (every
// k-th node: between half this number and this number).
constexpr size_t kMaxFootprintNodes = 100;

std::vector<NodeId> sampled(const Model& m, NodeId node, std::vector<NodeId> nodes) {
  if (nodes.size() <= kMaxFootprintNodes) return nodes;
  const Vec3& x0 = m.position(node);
  std::stable_sort(nodes.begin(), nodes.end(), [&](NodeId a, NodeId b) {
    return (m.position(a) - x0).squaredNorm() < (m.position(b) - x0).squaredNorm();
  });
  const size_t stride = (nodes.size() + kMaxFootprintNodes - 1) / kMaxFootprintNodes;
  std::vector<NodeId> out;
  for (size_t i = 0; i < nodes.size(); i += stride) out.push_back(nodes[i]);
  return out;
}

// The nodes of the shells around a node: never on one line.
std::vector<NodeId> ring(const std::vector<const ShellElement*>& shells) {
  std::set<NodeId> nodes;
  for (const ShellElement* e : shells) nodes.insert(e->nodes.begin(), e->nodes.end());
  return {nodes.begin(), nodes.end()};
}

std::vector<long> node_dofs(const Model& m, NodeId id, int count) {
  std::vector<long> d;
  const long base = 6 * static_cast<long>(m.node_index(id));
  for (int i = 0; i < count; ++i) d.push_back(base + i);
  return d;
}

// The mass on its node's translations, and its rotary inertia on the
// least-squares rigid rotation of the footprint (the rotation rows G of a
// distributing coupling over it): [u; G u_footprint].
// Nothing where even the shells around the node fix no rotation (elements
// so slender that their corners lie on a line to round-off).
std::optional<PointMassMatrix> on_footprint(const Model& m, NodeId node, const Eigen::Matrix<double, 6, 6>& M6,
                                            std::vector<NodeId> nodes, const std::vector<const ShellElement*>& shells) {
  std::vector<Vec3> x;
  for (NodeId id : nodes) x.push_back(m.position(id));
  std::optional<Eigen::MatrixXd> link = distributing_link(m.position(node), x, {});
  if (!link) {  // a sample of a strip's nodes can fall on one line
    nodes = ring(shells);
    x.clear();
    for (NodeId id : nodes) x.push_back(m.position(id));
    link = distributing_link(m.position(node), x, {});
  }
  if (!link) return std::nullopt;
  const Eigen::MatrixXd& G = *link;
  PointMassMatrix out;
  out.dofs = node_dofs(m, node, 6);
  std::vector<Eigen::Index> column;
  for (NodeId id : nodes) {
    if (id == node) {
      column.push_back(0);
      continue;
    }
    column.push_back(static_cast<Eigen::Index>(out.dofs.size()));
    for (long d : node_dofs(m, id, 3)) out.dofs.push_back(d);
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, static_cast<Eigen::Index>(out.dofs.size()));
  P.topLeftCorner<3, 3>().setIdentity();
  for (size_t j = 0; j < nodes.size(); ++j)
    P.block<3, 3>(3, column[j]) += G.block<3, 3>(3, 3 * static_cast<Eigen::Index>(j));
  out.M = P.transpose() * M6 * P;
  return out;
}

}  // namespace

std::vector<PointMassMatrix> point_mass_matrices(const Model& model) {
  // The shells at every shell node, where some mass has rotary inertia.
  ShellsAtNode shells_at;
  std::unordered_set<NodeId> carriers;
  const bool any_rotary = std::any_of(model.point_masses.begin(), model.point_masses.end(), [](const PointMass& p) {
    return point_mass_matrix(p).bottomRightCorner<3, 3>().norm() > 0.0;
  });
  if (any_rotary && !model.shells.empty()) {
    for (const ShellElement& s : model.shells)
      for (NodeId id : s.nodes) shells_at[id].push_back(&s);
    carriers = rotation_carriers(model);
  }
  std::vector<PointMassMatrix> out;
  out.reserve(model.point_masses.size());
  for (const PointMass& p : model.point_masses) {
    const Eigen::Matrix<double, 6, 6> M6 = point_mass_matrix(p);
    const auto it = shells_at.find(p.node);
    if (M6.bottomRightCorner<3, 3>().norm() > 0.0 && it != shells_at.end() && !carriers.count(p.node)) {
      const std::optional<Vec3> n = shell_plane_normal(model, it->second);
      const Eigen::Matrix3d J = M6.bottomRightCorner<3, 3>();
      if (n) {
        // The largest radius of gyration sizes the footprint.
        const double radius = p.mass > 0.0 ? std::sqrt(J.eigenvalues().real().maxCoeff() / p.mass) : 0.0;
        const std::vector<NodeId> nodes = sampled(model, p.node, footprint(model, shells_at, p.node, *n, radius));
        if (std::optional<PointMassMatrix> spread = on_footprint(model, p.node, M6, nodes, it->second)) {
          out.push_back(std::move(*spread));
          continue;
        }
      }
    }
    out.push_back({node_dofs(model, p.node, 6), M6});
  }
  return out;
}

}  // namespace rigflex::fe
