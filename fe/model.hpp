#pragma once
// The finite-element model of a frame: nodes, properties, elements, supports,
// rigid couplings and named node sets. Plain data; validate() checks it.
#include <Eigen/Dense>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "fe/material.hpp"
#include "fe/section.hpp"

namespace rigflex::fe {

using NodeId = long;
using Vec3 = Eigen::Vector3d;
using DofMask = std::array<bool, 6>;  // UX UY UZ RX RY RZ

enum class BeamTheory { Timoshenko, EulerBernoulli };
enum class MassKind { Consistent, Lumped, None };

struct Node {
  NodeId id = 0;
  Vec3 x = Vec3::Zero();
};

struct ShellSection {
  std::string name;
  std::string material;
  double thickness = 0.0;
  void validate() const;
};

struct BeamElement {
  std::string id;  // for messages; meshers generate "member:k"
  std::array<NodeId, 2> nodes{};
  std::string section;
  // Approximate direction of the section's local z ("height") axis; the
  // member axis is removed from it. Absent: global Z, or global X for members
  // within 1 degree of vertical.
  std::optional<Vec3> orientation;
  BeamTheory theory = BeamTheory::Timoshenko;
  MassKind mass = MassKind::Consistent;
  // Rotary inertia of the cross-sections in bending (rho I). Classical
  // Euler-Bernoulli closed forms leave it out; torsional inertia always stays.
  bool rotary_inertia = true;
};

struct ShellElement {
  std::string id;
  // 4 corners counter-clockwise, or 4 corners then mid-sides 1-2, 2-3, 3-4,
  // 4-1: the node count chooses the element type (fe/shell_types.hpp).
  std::vector<NodeId> nodes;
  std::string section;
  MassKind mass = MassKind::Consistent;
  // A node generated for the element's own coordinates (an 8-node shell's
  // centre: add_shell_centres()), touched by nothing else; 0: none, and the
  // element condenses them statically.
  NodeId centre = 0;
};

// A continuum element (fe/solid_types.hpp): 8, 20 or 10 nodes choose hex8,
// hex20 or tet10; its nodes' translations only.
struct SolidElement {
  std::string id;
  std::vector<NodeId> nodes;
  std::string material;
  MassKind mass = MassKind::Consistent;
};

struct PointMass {
  std::string id;
  NodeId node = 0;
  double mass = 0.0;
  // Inertia about the node, global axes, [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] with
  // the negative-integral products of shared/spec/rig-conventions.md.
  std::array<double, 6> inertia{};
};

struct Spring {
  std::string id;
  NodeId node = 0;
  std::optional<NodeId> other;  // absent: to ground
  // Either six uncoupled stiffnesses in global axes [N/m, N m/rad] ...
  std::array<double, 6> stiffness{};
  // ... or an axial spring along a direction (node-node default: the line
  // between the nodes).
  std::optional<double> axial;
  std::optional<Vec3> direction;
};

struct Support {
  std::string id;
  NodeId node = 0;
  DofMask fixed{};
};

// Kinematic coupling (RBE2): the coupled DOFs of each dependent node follow
// the rigid motion of the reference node exactly.
struct RigidCoupling {
  std::string id;
  NodeId reference = 0;
  std::vector<NodeId> dependents;
  DofMask dofs{true, true, true, true, true, true};
};

// Distributing coupling (RBE3): the reference node's six DOFs follow the
// weighted least-squares rigid motion of the nodes' translations. Unlike
// RigidCoupling it adds no stiffness among the nodes: a load or a mass at the
// reference spreads over them as statics would spread it onto a rigid body,
// and the face it is attached to deforms freely (fe/distributing_coupling.hpp).
struct DistributingCoupling {
  std::string id;
  NodeId reference = 0;
  std::vector<NodeId> nodes;
  std::vector<double> weights;  // one per node; empty: all 1
};

// A reduced part placed in the model (a superelement): its stiffness and
// mass on chosen DOFs of model nodes (its interface) and on generalized
// coordinates (a Craig-Bampton reduction's fixed-interface modal
// coordinates). Each generalized coordinate is carried by the first DOF
// (UX) of a node of its own (`modal_nodes`: generated where the part is
// placed, touched by nothing else; their other DOFs stay unused and are
// dropped). Their DOFs are amplitudes, not displacements: rigid-body
// motions give them zero (fe/mass_properties.hpp).
struct SuperelementDof {
  NodeId node = 0;
  int local = 0;  // 0..5 = UX UY UZ RX RY RZ
};

struct Superelement {
  std::string id;
  std::vector<SuperelementDof> interface;  // the first rows of K and M
  std::vector<NodeId> modal_nodes;         // the last rows: one generalized coordinate each
  Eigen::MatrixXd K, M;                    // symmetric, (interface + modal)^2
  bool grounded = false;                   // reduced with its own supports: it holds the model
};

class Model {
 public:
  std::vector<Node> nodes;
  std::map<std::string, Material> materials;
  std::map<std::string, BeamSection> beam_sections;
  std::map<std::string, ShellSection> shell_sections;
  std::vector<BeamElement> beams;
  std::vector<ShellElement> shells;
  std::vector<SolidElement> solids;
  std::vector<PointMass> point_masses;
  std::vector<Spring> springs;
  std::vector<Support> supports;
  std::vector<RigidCoupling> couplings;
  std::vector<DistributingCoupling> distributing_couplings;
  std::vector<Superelement> superelements;
  std::map<std::string, std::vector<NodeId>> node_sets;

  // Adds a node; throws ModelError on a duplicate id.
  NodeId add_node(NodeId id, const Vec3& x);
  NodeId next_node_id() const;

  bool has_node(NodeId id) const { return index_.count(id) != 0; }
  // Index of a node in `nodes`; throws ModelError if absent.
  size_t node_index(NodeId id) const;
  const Vec3& position(NodeId id) const { return nodes[node_index(id)].x; }
  std::vector<NodeId> node_set(const std::string& name) const;  // throws if absent

  // Checks every property and element; throws ModelError naming the entity.
  void validate() const;
  // Rebuilds the id index after `nodes` was edited directly.
  void reindex();

 private:
  std::unordered_map<NodeId, size_t> index_;
};

}  // namespace rigflex::fe
