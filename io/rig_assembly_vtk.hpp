#pragma once
// The rig assembled for ParaView: one .vtu (rig_assembly.vtu from `rigflex
// check --out`) with the fixed frame, the rods, the carrying frame and the
// suspended body at the static equilibrium, in G (m). Each cell's
// `component` says what it belongs to; `element_kind` which element an FE
// cell is (io/vtk_mesh.hpp) or what the other cells are.
//   - A frame given as an FE model shows its mesh as built (undeformed; its
//     couplings as lines from the reference node to each node tied),
//     the carrying frame's moved to the body's equilibrium pose; the joints,
//     and so the rods' ends, sit where the loaded frames hold them (a soft
//     fixed frame lets them down by centimetres: field data
//     `fixed_frame_joint_deflection` and `carrying_frame_joint_deflection`,
//     the largest joint displacement, m); a frame given
//     as a reduced export shows the polygon through its interface nodes; a
//     rigid frame the polygon through its joints (and the carrying frame's
//     lines from the reference point P to its joints).
//   - The body (what hangs from the rods: carrying frame and body, as
//     rig::RigAssembly::body) shows as its equivalent box: the same mass,
//     CoG and inertia tensor (sides along the principal axes,
//     a^2 = 6 (J2 + J3 - J1) / m, ...); field data `body_mass` and
//     `box_sides`.
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

#include "fe/model.hpp"
#include "io/atomic_file.hpp"
#include "rig/rig_spec.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::io {

// How a frame is drawn: its FE mesh if there is one, else the interface
// nodes of its reduced export.
struct AssemblyFrame {
  const fe::Model* mesh = nullptr;                   // not owned (read while the file is queued)
  std::vector<Eigen::Vector3d> interface_nodes;      // model coordinates, in set order
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // added to model coordinates: G (fixed), frame c (carrying)
};

struct AssemblyFrames {
  std::optional<AssemblyFrame> fixed, carrying;  // none: a rigid frame, drawn through its joints
};

// The frames a rig file gives (its frame models and reduced exports), from
// the spec before rig::resolve_frames; they point into `spec`.
AssemblyFrames assembly_frames(const rig::RigSpec& spec);

// `component` values.
enum AssemblyComponent : int { kFixedFrame = 1, kRods = 2, kCarryingFrame = 3, kBody = 4 };
// `element_kind` values of the cells that are not FE elements.
enum AssemblyCellKind : int { kOutlineCell = 5, kRodCell = 6, kBodyBoxCell = 7, kCouplingCell = 8 };

// The sides (m) and axes (columns, frame c, right-handed) of the box with
// the mass properties `body`; a side whose square comes out negative (a
// rounding at the triangle inequality's edge) is 0.
struct EquivalentBox {
  Eigen::Vector3d sides;
  Eigen::Matrix3d axes;
};
EquivalentBox equivalent_box(const fe::MassProperties& body);

// Queues `file` into `batch`.
void add_rig_assembly_file(FileBatch& batch, const std::filesystem::path& file, const rig::RigSystem& rig,
                           const rig::Configuration& equilibrium, const AssemblyFrames& frames);

}  // namespace rigflex::io
