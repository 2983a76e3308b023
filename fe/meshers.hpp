#pragma once
// Parametric meshers: beam members, shell patches, solid blocks, box girders,
// and the two frame kinds of a multi-filar pendulum rig.
#include <optional>
#include <string>
#include <vector>

#include "fe/model.hpp"
#include "fe/node_merger.hpp"

namespace rigflex::fe {

struct MemberSpec {
  std::string id;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
  int elements = 1;
  std::string section;
  std::optional<Vec3> orientation;
  BeamTheory theory = BeamTheory::Timoshenko;
  MassKind mass = MassKind::Consistent;
  bool rotary_inertia = true;
  // Extra stations (fractions in (0,1) of the length) that must be nodes,
  // for example where a joint bracket attaches.
  std::vector<double> stations;
};
// Returns the member's node ids from `from` to `to`.
std::vector<NodeId> mesh_member(Model& model, NodeMerger& merger, const MemberSpec& spec);

struct PatchSpec {
  std::string id;
  std::array<Vec3, 4> corners{};  // counter-clockwise seen from the normal side
  int nx = 1, ny = 1;             // divisions along corner 1->2 and 1->4
  bool quadratic = false;         // 8-node elements instead of MITC4
  std::string section;
  MassKind mass = MassKind::Consistent;
};
struct PatchNodes {
  int rows = 0, cols = 0;  // grid of nodes, row-major; mid-face points of 8-node grids are absent (0)
  std::vector<NodeId> ids;
  NodeId at(int row, int col) const { return ids[static_cast<size_t>(row * cols + col)]; }
};
PatchNodes mesh_shell_patch(Model& model, NodeMerger& merger, const PatchSpec& spec);

struct SolidBlockSpec {
  std::string id;
  // A hexahedron in hex8 node order (fe/solid_element.hpp): 1-4 counter-
  // clockwise seen from 5's side; mapped trilinearly, so faces may be warped.
  std::array<Vec3, 8> corners{};
  int nx = 1, ny = 1, nz = 1;    // divisions along corner 1->2, 1->4, 1->5
  std::string element = "hex8";  // a solid type's name; tet10 splits each cell into 6
  std::string material;
  MassKind mass = MassKind::Consistent;
};
// Returns the number of elements made.
long mesh_solid_block(Model& model, NodeMerger& merger, const SolidBlockSpec& spec);

struct BoxGirderSpec {
  std::string id;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // axis end points (section centres)
  Vec3 up = Vec3::UnitZ();                      // approximate direction of the height
  double width = 0.0, height = 0.0;             // outer dimensions
  double web_thickness = 0.0, flange_thickness = 0.0;
  std::string material;
  int n_along = 4, n_width = 1, n_height = 1;
  bool quadratic = false;
  bool end_plates = true;     // closing diaphragms at both ends
  bool end_couplings = true;  // reference nodes at the axis end points, rigidly coupled to the end sections
  MassKind mass = MassKind::Consistent;
};
struct BoxGirderNodes {
  std::optional<NodeId> start_reference, end_reference;
};
BoxGirderNodes mesh_box_girder(Model& model, NodeMerger& merger, const BoxGirderSpec& spec);

// Fixed frame: columns clamped at the floor, cross beams between column tops
// (a closed ring, plus extra pairs), and the upper joint centres hung from
// the nearest cross beam through rigid couplings. Node set "upper_joints".
struct FixedFrameSpec {
  std::string id = "fixed_frame";
  std::vector<Vec3> column_bases;  // floor points
  double height = 0.0;
  std::string column_section, beam_section;
  std::vector<std::array<int, 2>> extra_beams;  // column indices (0-based)
  bool ring = true;                              // beams between consecutive column tops
  std::vector<Vec3> joints;                      // upper joint centres A_i
  int elements_per_member = 4;
  std::string joint_set = "upper_joints";
};
void build_fixed_frame(Model& model, const FixedFrameSpec& spec);

// Carrying frame: a rectangular grid of beams in the plane z = level, with
// the lower joint centres coupled rigidly to the nearest grid node. Floating
// (no supports). Node set "lower_joints".
struct CarryingFrameSpec {
  std::string id = "carrying_frame";
  Vec3 corner_min = Vec3::Zero();  // x, y of one corner and z of the grid plane
  Vec3 corner_max = Vec3::Zero();  // x, y of the opposite corner (z ignored)
  int bays_x = 1, bays_y = 1;
  std::string section;
  std::vector<Vec3> joints;  // lower joint centres B_i
  int elements_per_member = 2;
  std::string joint_set = "lower_joints";
};
void build_carrying_frame(Model& model, const CarryingFrameSpec& spec);

}  // namespace rigflex::fe
