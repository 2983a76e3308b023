#include "fe/model.hpp"

#include <cmath>
#include <set>

#include "fe/distributing_coupling.hpp"
#include "fe/dof.hpp"
#include "fe/error.hpp"
#include "fe/shell_element.hpp"
#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::fe {

void ShellSection::validate() const {
  if (!(std::isfinite(thickness) && thickness > 0.0))
    throw ModelError({"shell_section", name, "thickness"},
                     "shell section '" + name + "': thickness must be positive");
}

NodeId Model::add_node(NodeId id, const Vec3& x) {
  if (index_.count(id) != 0)
    throw ModelError({"node", std::to_string(id), "id"}, "duplicate node id " + std::to_string(id));
  if (!x.allFinite())
    throw ModelError({"node", std::to_string(id), "x"}, "node " + std::to_string(id) + ": non-finite coordinate");
  index_[id] = nodes.size();
  nodes.push_back({id, x});
  return id;
}

NodeId Model::next_node_id() const {
  NodeId m = 0;
  for (const Node& n : nodes) m = std::max(m, n.id);
  return m + 1;
}

size_t Model::node_index(NodeId id) const {
  auto it = index_.find(id);
  if (it == index_.end())
    throw ModelError({"node", std::to_string(id), ""}, "node " + std::to_string(id) + " does not exist");
  return it->second;
}

std::vector<NodeId> Model::node_set(const std::string& name) const {
  auto it = node_sets.find(name);
  if (it == node_sets.end()) throw ModelError({"node_set", name, ""}, "node set '" + name + "' does not exist");
  return it->second;
}

void Model::reindex() {
  index_.clear();
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!index_.emplace(nodes[i].id, i).second)
      throw ModelError({"node", std::to_string(nodes[i].id), "id"},
                       "duplicate node id " + std::to_string(nodes[i].id));
  }
}

namespace {

void require_node(const Model& m, NodeId id, const EntityRef& where, const std::string& what) {
  if (!m.has_node(id))
    throw ModelError(where, what + " refers to node " + std::to_string(id) + ", which does not exist");
}

template <class Map>
const auto& require_property(const Map& map, const std::string& name, const EntityRef& where,
                             const std::string& what, const std::string& kind) {
  auto it = map.find(name);
  if (it == map.end()) throw ModelError(where, what + " refers to " + kind + " '" + name + "', which does not exist");
  return it->second;
}

void validate_beam(const Model& m, const BeamElement& b) {
  const EntityRef where{"beam", b.id, "nodes"};
  const std::string what = "beam '" + b.id + "'";
  for (NodeId n : b.nodes) require_node(m, n, where, what);
  const auto& sec = require_property(m.beam_sections, b.section, {"beam", b.id, "section"}, what, "beam section");
  require_property(m.materials, sec.material, {"beam_section", sec.name, "material"},
                   "beam section '" + sec.name + "'", "material");
  const Vec3 axis = m.position(b.nodes[1]) - m.position(b.nodes[0]);
  const double L = axis.norm();
  if (!(L > 0.0)) throw ModelError(where, what + " has zero length (its nodes coincide)");
  if (b.orientation) {
    const Vec3 v = *b.orientation;
    if (!(v.norm() > 0.0) || v.normalized().cross(axis / L).norm() < 1e-6)
      throw ModelError({"beam", b.id, "orientation"}, what + ": orientation vector is zero or parallel to the member");
  }
}

void validate_shell(const Model& m, const ShellElement& s) {
  const std::string what = "shell '" + s.id + "'";
  if (!shell_type_with_nodes(s.nodes.size()))
    throw ModelError({"shell", s.id, "nodes"}, what + " must have " + shell_node_counts() + " nodes");
  std::vector<Vec3> x;
  for (NodeId n : s.nodes) {
    require_node(m, n, {"shell", s.id, "nodes"}, what);
    x.push_back(m.position(n));
  }
  const auto& sec = require_property(m.shell_sections, s.section, {"shell", s.id, "section"}, what, "shell section");
  require_property(m.materials, sec.material, {"shell_section", sec.name, "material"},
                   "shell section '" + sec.name + "'", "material");
  check_shell_geometry(x, s.id);
  if (s.centre == 0) return;
  require_node(m, s.centre, {"shell", s.id, "nodes"}, what);
  const ShellType& type = *shell_type_with_nodes(s.nodes.size());
  if (type.own_coordinates == 0 || s.mass != MassKind::Consistent)
    throw ModelError({"shell", s.id, "mass"}, what + ": a centre node needs an 8-node shell with consistent mass");
  for (NodeId n : s.nodes)
    if (n == s.centre) throw ModelError({"shell", s.id, "nodes"}, what + ": its centre node is one of its nodes");
}

void validate_solid(const Model& m, const SolidElement& s) {
  const std::string what = "solid '" + s.id + "'";
  if (!solid_type_with_nodes(s.nodes.size()))
    throw ModelError({"solid", s.id, "nodes"}, what + " must have " + solid_node_counts() + " nodes");
  std::vector<Vec3> x;
  std::set<NodeId> seen;
  for (NodeId n : s.nodes) {
    require_node(m, n, {"solid", s.id, "nodes"}, what);
    if (!seen.insert(n).second)
      throw ModelError({"solid", s.id, "nodes"}, what + " lists node " + std::to_string(n) + " twice");
    x.push_back(m.position(n));
  }
  require_property(m.materials, s.material, {"solid", s.id, "material"}, what, "material");
  // A mirrored node order is the usual cause; a ratio near zero is a
  // collapsed element whose matrices would be meaningless.
  const double ratio = solid_jacobian_ratio(x);
  if (!(ratio > 1e-6))
    throw ModelError(
        {"solid", s.id, "nodes"},
        what + ": inverted or degenerate (smallest Jacobian determinant " + std::to_string(ratio) + " of the mean); " +
            (s.nodes.size() == 10 ? "corner 4 must lie on the side of corners 1-2-3 where (x2 - x1) x (x3 - x1) points"
                                  : "corners 1-4 must run counter-clockwise seen from corner 5's side") +
            " (fe/solid_element.hpp)");
}

void validate_point_mass(const Model& m, const PointMass& p) {
  const std::string what = "point mass '" + p.id + "'";
  require_node(m, p.node, {"point_mass", p.id, "node"}, what);
  if (!(std::isfinite(p.mass) && p.mass >= 0.0))
    throw ModelError({"point_mass", p.id, "mass"}, what + ": mass must be non-negative");
  const auto& J = p.inertia;
  Eigen::Matrix3d T;
  T << J[0], J[3], J[4], J[3], J[1], J[5], J[4], J[5], J[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(T);
  const double scale = std::max(1.0, T.cwiseAbs().maxCoeff());
  if (!T.allFinite() || es.eigenvalues().minCoeff() < -1e-12 * scale)
    throw ModelError({"point_mass", p.id, "inertia"}, what + ": inertia tensor is not positive semi-definite");
}

void validate_spring(const Model& m, const Spring& s) {
  const std::string what = "spring '" + s.id + "'";
  require_node(m, s.node, {"spring", s.id, "node"}, what);
  if (s.other) {
    require_node(m, *s.other, {"spring", s.id, "other"}, what);
    if (*s.other == s.node) throw ModelError({"spring", s.id, "other"}, what + " connects a node to itself");
  }
  for (double k : s.stiffness)
    if (!(std::isfinite(k) && k >= 0.0))
      throw ModelError({"spring", s.id, "stiffness"}, what + ": stiffness must be non-negative");
  if (s.axial) {
    if (!(std::isfinite(*s.axial) && *s.axial >= 0.0))
      throw ModelError({"spring", s.id, "axial"}, what + ": axial stiffness must be non-negative");
    Vec3 d = s.direction.value_or(Vec3::Zero());
    if (!s.direction && s.other) d = m.position(*s.other) - m.position(s.node);
    if (!(d.norm() > 0.0))
      throw ModelError({"spring", s.id, "direction"},
                       what + ": an axial spring needs a direction (or two distinct nodes)");
  }
}

void validate_coupling(const Model& m, const RigidCoupling& c, std::set<NodeId>& dependents_seen) {
  const std::string what = "rigid coupling '" + c.id + "'";
  require_node(m, c.reference, {"coupling", c.id, "reference"}, what);
  if (c.dependents.empty()) throw ModelError({"coupling", c.id, "nodes"}, what + " has no dependent nodes");
  for (NodeId d : c.dependents) {
    require_node(m, d, {"coupling", c.id, "nodes"}, what);
    if (d == c.reference)
      throw ModelError({"coupling", c.id, "nodes"}, what + ": the reference node is also a dependent");
    if (!dependents_seen.insert(d).second)
      throw ModelError({"coupling", c.id, "nodes"},
                       what + ": node " + std::to_string(d) + " is already the dependent of another coupling");
    // A dependent on top of its reference is a mesh error (two nodes where
    // one was meant), not a rigid link.
    if ((m.position(d) - m.position(c.reference)).norm() == 0.0)
      throw ModelError({"coupling", c.id, "nodes"},
                       what + ": dependent node " + std::to_string(d) + " coincides with the reference node");
  }
  bool any = false;
  for (bool b : c.dofs) any = any || b;
  if (!any) throw ModelError({"coupling", c.id, "dofs"}, what + " couples no DOF");
}

// Chains (a coupling's node driven by another coupling) would need the
// couplings composed; they are refused, naming both.
void validate_distributing(const Model& m, const DistributingCoupling& c, const std::set<NodeId>& rigid_dependents,
                           const std::set<NodeId>& all_references, std::set<NodeId>& references) {
  const std::string what = "distributing coupling '" + c.id + "'";
  require_node(m, c.reference, {"coupling", c.id, "reference"}, what);
  if (c.nodes.empty()) throw ModelError({"coupling", c.id, "nodes"}, what + " has no nodes");
  if (!c.weights.empty() && c.weights.size() != c.nodes.size())
    throw ModelError({"coupling", c.id, "weights"}, what + ": " + std::to_string(c.weights.size()) + " weights for " +
                                                        std::to_string(c.nodes.size()) + " nodes");
  for (double w : c.weights)
    if (!(std::isfinite(w) && w > 0.0))
      throw ModelError({"coupling", c.id, "weights"}, what + ": weights must be positive");
  if (rigid_dependents.count(c.reference))
    throw ModelError({"coupling", c.id, "reference"},
                     what + ": its reference node " + std::to_string(c.reference) +
                         " is the dependent of a rigid coupling (chained couplings are not supported)");
  if (!references.insert(c.reference).second)
    throw ModelError({"coupling", c.id, "reference"}, what + ": node " + std::to_string(c.reference) +
                                                          " is already the reference of a distributing coupling");
  std::set<NodeId> seen;
  std::vector<Vec3> x;
  for (NodeId n : c.nodes) {
    require_node(m, n, {"coupling", c.id, "nodes"}, what);
    if (n == c.reference)
      throw ModelError({"coupling", c.id, "nodes"}, what + ": the reference node is also one of its nodes");
    if (!seen.insert(n).second)
      throw ModelError({"coupling", c.id, "nodes"}, what + " lists node " + std::to_string(n) + " twice");
    if (rigid_dependents.count(n))
      throw ModelError({"coupling", c.id, "nodes"},
                       what + ": node " + std::to_string(n) +
                           " is the dependent of a rigid coupling (chained couplings are not supported)");
    if (all_references.count(n))
      throw ModelError({"coupling", c.id, "nodes"},
                       what + ": node " + std::to_string(n) +
                           " is the reference of a distributing coupling (chained couplings are not supported)");
    x.push_back(m.position(n));
  }
  if (!distributing_link(m.position(c.reference), x, c.weights))
    throw ModelError({"coupling", c.id, "nodes"},
                     what +
                         ": its nodes lie on one line (or are fewer than three), so they do not define the "
                         "reference's rotation; add nodes off the line");
}

}  // namespace

namespace {

// A shell's centre node carries the element's own coordinates (amplitudes,
// not a place): anything else attached to it would read them as motions.
void require_centres_untouched(const Model& m, const std::set<NodeId>& centres) {
  if (centres.empty()) return;
  auto check = [&](NodeId id, const char* kind, const std::string& entity) {
    if (centres.count(id))
      throw ModelError({kind, entity, ""}, std::string(kind) + " '" + entity + "': node " + std::to_string(id) +
                                               " carries an 8-node shell's centre coordinates; nothing else may "
                                               "use it (add supports, masses and couplings before the centres)");
  };
  for (const auto& b : m.beams)
    for (NodeId id : b.nodes) check(id, "beam", b.id);
  for (const auto& s : m.shells)
    for (NodeId id : s.nodes) check(id, "shell", s.id);
  for (const auto& s : m.solids)
    for (NodeId id : s.nodes) check(id, "solid", s.id);
  for (const auto& p : m.point_masses) check(p.node, "point_mass", p.id);
  for (const auto& s : m.springs) {
    check(s.node, "spring", s.id);
    if (s.other) check(*s.other, "spring", s.id);
  }
  for (const auto& s : m.supports) check(s.node, "support", s.id);
  for (const auto& c : m.couplings) {
    check(c.reference, "coupling", c.id);
    for (NodeId id : c.dependents) check(id, "coupling", c.id);
  }
  for (const auto& c : m.distributing_couplings) {
    check(c.reference, "coupling", c.id);
    for (NodeId id : c.nodes) check(id, "coupling", c.id);
  }
  for (const auto& e : m.superelements) {
    for (const SuperelementDof& d : e.interface) check(d.node, "superelement", e.id);
    for (NodeId id : e.modal_nodes) check(id, "superelement", e.id);
  }
}

void validate_superelement(const Model& model, const Superelement& e) {
  const EntityRef where{"superelement", e.id, ""};
  const std::string what = "superelement '" + e.id + "'";
  const auto n = static_cast<Eigen::Index>(e.interface.size() + e.modal_nodes.size());
  if (e.interface.empty()) throw ModelError(where, what + " has no interface DOF");
  if (e.K.rows() != n || e.K.cols() != n || e.M.rows() != n || e.M.cols() != n)
    throw ModelError(where, what + ": K and M must be " + std::to_string(n) + " x " + std::to_string(n) +
                                " (interface DOFs and modal coordinates)");
  if (!e.K.allFinite() || !e.M.allFinite()) throw ModelError(where, what + ": K or M is not finite");
  const double scale_k = std::max(e.K.cwiseAbs().maxCoeff(), 1e-300),
               scale_m = std::max(e.M.cwiseAbs().maxCoeff(), 1e-300);
  if ((e.K - e.K.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale_k ||
      (e.M - e.M.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale_m)
    throw ModelError(where, what + ": K and M must be symmetric");
  std::set<std::pair<NodeId, int>> seen;
  for (const SuperelementDof& d : e.interface) {
    require_node(model, d.node, where, what);
    if (d.local < 0 || d.local > 5) throw ModelError(where, what + ": a DOF index outside 0..5");
    if (!seen.insert({d.node, d.local}).second)
      throw ModelError(where, what + ": node " + std::to_string(d.node) + " " + std::string(dof_name(d.local)) +
                                  " is an interface DOF twice");
  }
  std::set<NodeId> modal;
  for (NodeId id : e.modal_nodes) {
    require_node(model, id, where, what);
    if (!modal.insert(id).second || seen.count({id, 0}))
      throw ModelError(where, what + ": node " + std::to_string(id) + " carries two coordinates");
  }
}

}  // namespace

void Model::validate() const {
  for (const auto& [name, mat] : materials) mat.validate();
  for (const auto& [name, sec] : beam_sections) sec.validate();
  for (const auto& [name, sec] : shell_sections) sec.validate();
  for (const auto& b : beams) validate_beam(*this, b);
  std::set<NodeId> centres;
  for (const auto& s : shells) {
    validate_shell(*this, s);
    if (s.centre != 0 && !centres.insert(s.centre).second)
      throw ModelError({"shell", s.id, "nodes"}, "shell '" + s.id + "': its centre node " + std::to_string(s.centre) +
                                                     " is another shell's centre too");
  }
  for (const auto& s : solids) validate_solid(*this, s);
  for (const auto& p : point_masses) validate_point_mass(*this, p);
  for (const auto& s : springs) validate_spring(*this, s);
  for (const auto& s : supports) require_node(*this, s.node, {"support", s.id, "node"}, "support '" + s.id + "'");
  std::set<NodeId> dependents;
  for (const auto& c : couplings) validate_coupling(*this, c, dependents);
  for (const auto& c : couplings)
    if (dependents.count(c.reference))
      throw ModelError({"coupling", c.id, "reference"},
                       "rigid coupling '" + c.id + "': its reference node " + std::to_string(c.reference) +
                           " is the dependent of another coupling (chained couplings are not supported)");
  std::set<NodeId> all_references, distributing_references;
  for (const auto& c : distributing_couplings) all_references.insert(c.reference);
  for (const auto& c : distributing_couplings)
    validate_distributing(*this, c, dependents, all_references, distributing_references);
  for (const auto& c : couplings)
    if (distributing_references.count(c.reference))
      throw ModelError({"coupling", c.id, "reference"},
                       "rigid coupling '" + c.id + "': its reference node " + std::to_string(c.reference) +
                           " is driven by a distributing coupling (chained couplings are not supported)");
  for (const auto& [name, ids] : node_sets)
    for (NodeId id : ids) require_node(*this, id, {"node_set", name, ""}, "node set '" + name + "'");
  for (const auto& e : superelements) validate_superelement(*this, e);
  require_centres_untouched(*this, centres);
}

}  // namespace rigflex::fe
