#pragma once
// The CalculiX / Abaqus input deck of a rigflex model: a *FREQUENCY analysis
// of the same frame (rigflex export --deck; the CalculiX cross-checks of
// tests/verification run it through ccx 2.20). Abaqus reads the same deck
// with CalculixDialect::abaqus.
//
// How the model maps onto ccx:
//   beams      -> B32R (3 nodes: a mid node is generated at each midpoint).
//                 ccx has no true beam element: it expands every B32(R) into
//                 a 20-node brick (C3D20R for B32R) over the section's
//                 bounding rectangle, and models PIPE and BOX sections by
//                 placing integration points on the walls. Reduced
//                 integration (B32R rather than B32/C3D20): ccx's PIPE and
//                 BOX sections are integration schemes of the B32R parent
//                 element, and one element type keeps all sections
//                 comparable. B31 is not used: ccx's linear beam (C3D8I)
//                 refuses CIRC sections, and a linear interpolation needs
//                 more nodes for the same bending accuracy.
//                 BeamTheory::EulerBernoulli has no ccx counterpart (the
//                 solid always deforms in shear); it is written unchanged.
//   sections   -> *BEAM SECTION RECT, CIRC, PIPE, BOX. I-sections and
//                 general sections (A, Iy, Iz, J) have no ccx 2.20 *BEAM
//                 SECTION equivalent for B32R (GENERAL only serves the U1
//                 user element): std::invalid_argument naming the section.
//   orientation-> ccx's 1-direction n1 is given on the third line of *BEAM
//                 SECTION and its 2-direction is n2 = t x n1 (t: the beam
//                 tangent). rigflex's local axes are ex = t, ey = up x ex,
//                 ez = ex x ey with width along ey and height along ez
//                 (fe::beam_local_axes). Writing n1 = ey gives n2 = ex x ey
//                 = ez, so "thickness in 1-direction" = width and
//                 "thickness in 2-direction" = height; for BOX (a, b, t1..t4
//                 with t1 the wall at +n1, t2 at +n2, t3 at -n1, t4 at -n2)
//                 a = width, b = height, t1 = t3 = web, t2 = t4 = flange.
//   shells     -> MITC4: S4 (expanded by ccx into a C3D8I brick, fully
//                 integrated with incompatible modes, so it neither locks in
//                 bending nor shows the hourglass modes of S4R/C3D8R with one
//                 element through the thickness). 8-node shells: S8R
//                 (C3D20R; ccx's recommended shell; S8/C3D20 locks in thin
//                 bending).
//   materials  -> *MATERIAL, *ELASTIC, *DENSITY; elements with
//                 MassKind::None get a zero-density copy of their material.
//                 Lumped beam/shell mass is written as ccx's consistent mass.
//   supports   -> *BOUNDARY (rotations of beam/shell nodes are constrained
//                 by ccx through a "knot" or a mean-rotation MPC).
//   couplings  -> linear *EQUATIONs of a rigid link (RBE2) from the
//                 reference to each dependent, the reference's rotation held
//                 by a generated rotation node (ccx's ROT NODE convention);
//                 beam and shell nodes in a coupling also get their rotations
//                 tied, and a short, massless, free "knot anchor" beam so
//                 that ccx gives them rotational DOFs at all (see
//                 calculix_deck.cpp). *RIGID BODY is not used: in ccx 2.20
//                 it ties only translations of beam and shell nodes, and
//                 leaves the rotation about the line free when the nodes
//                 are collinear (a single dependent). Only couplings
//                 of all six DOFs are supported (std::invalid_argument).
//   point mass -> MASS element; CalculiX 2.20 has no rotary inertia for MASS
//                 elements, so a nonzero inertia throws std::invalid_argument.
//   springs    -> SPRING1 (to ground) / SPRING2 (node to node) per
//                 translational DOF, SPRINGA for axial springs (to ground
//                 along `direction` through a generated clamped node).
//                 Rotational spring stiffnesses throw std::invalid_argument.
//
// Because ccx solves a 3D solid (C3D20R / C3D8I) model of every beam and
// shell, its frequencies differ from rigflex's beam and shell theory by the
// modelling: shear and warping of the solid section, St-Venant torsion of the
// expanded rectangle instead of the section's torsion constant J (thin-walled
// BOX/PIPE torsion is only approximated), and rigid "knots" where members
// meet at an angle. Tolerances against rigflex must account for that; see
// tests/io/test_calculix_crosscheck.cpp.
#include <string>
#include <unordered_map>

#include "fe/model.hpp"

namespace rigflex::io {

// Which program reads the deck: the keywords are the same, a few data lines
// differ (CIRC: CalculiX takes the two diameters of an ellipse, Abaqus the
// radius; SPRINGA: Abaqus wants an empty first data line).
enum class CalculixDialect { calculix, abaqus };

struct CalculixOptions {
  CalculixDialect dialect = CalculixDialect::calculix;
  int modes = 10;               // eigenfrequencies requested from *FREQUENCY
  std::string heading;          // *HEADING text (optional)
  bool write_node_file = true;  // *NODE FILE U: mode shapes in job.frd
  // *FREQUENCY, SOLVER=MATRIXSTORAGE: ccx stores its stiffness and mass
  // (job.sti, job.mas, job.dof, see run_calculix_matrices) instead of
  // solving; `modes` and `write_node_file` are then without effect.
  bool matrix_storage = false;
  // Throws std::invalid_argument naming the offending option.
  void validate() const;
};

// The complete .inp text. Throws fe::ModelError for an invalid model and
// std::invalid_argument (naming the entity) for model content that ccx 2.20
// cannot express (see above).
std::string calculix_input(const fe::Model& model, const CalculixOptions& opt);

// The deck with the numbering it gave the model's nodes (rigflex id -> ccx
// label); labels from first_free_node on are the writer's own nodes.
struct CalculixDeck {
  std::string text;
  std::unordered_map<fe::NodeId, long> ccx_ids;
  long first_free_node = 0;
};
CalculixDeck calculix_deck(const fe::Model& model, const CalculixOptions& opt);

}  // namespace rigflex::io
