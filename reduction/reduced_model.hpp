#pragma once
// A frame reduced onto its interface (joint) DOFs: what the rig model, the
// identifier and the exports share. Units SI: K in N/m (N m/rad for rotations),
// M in kg (kg m^2), C in N s/m.
//
// Reduced coordinates, in this order: the interface DOFs, node by node in the
// interface set's order, UX UY UZ (then RX RY RZ when all six are retained);
// then, for Craig-Bampton, the modal coordinates q_1..q_N of the
// fixed-interface normal modes (M-normalized, so their block of K is
// diag(omega_k^2) and of M the identity).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fe/mass_properties.hpp"
#include "fe/model.hpp"

namespace rigflex::reduction {

enum class ReductionMethod { guyan, craig_bampton };

// How the frame is held while it is reduced.
enum class FrameSupport {
  grounded,        // by the model's own supports (the fixed frame at the floor)
  free,            // free-free: the six rigid-body modes stay in the reduced model
  reference_node,  // floating, all six DOFs of one chosen node held (e.g. the
                   // CoG of carrying frame + body); the model has no supports
};

// Which DOFs of each interface node are retained.
enum class InterfaceDofs { translations, all };

const char* to_string(ReductionMethod m);    // "guyan", "craig-bampton"
const char* to_string(FrameSupport s);       // "grounded", "free", "reference-node"
const char* to_string(InterfaceDofs d);      // "translations", "all"
// Inverse of to_string; std::nullopt for an unknown name.
std::optional<ReductionMethod> parse_reduction_method(const std::string& s);
std::optional<FrameSupport> parse_frame_support(const std::string& s);
std::optional<InterfaceDofs> parse_interface_dofs(const std::string& s);

struct InterfaceNode {
  fe::NodeId id = 0;
  fe::Vec3 position = fe::Vec3::Zero();  // m, global
};

struct InterfaceDof {
  fe::NodeId node = 0;
  int local = 0;  // 0..5 = UX UY UZ RX RY RZ (fe/dof.hpp)
};

// C = alpha M + beta K, chosen so that the damping ratio is zeta[k] at the
// elastic modes `modes` of the full model (1-based, rigid-body modes not
// counted): zeta(omega) = alpha / (2 omega) + beta omega / 2. For a
// free-free frame the mass-proportional term is restricted to the elastic
// subspace, alpha (M - M R (R' M R)^-1 R' M) with R the rigid-body motions,
// so that swinging and turning as a rigid body is not damped (plain alpha M
// would brake the pendulum) while every elastic mode keeps the same ratio.
struct RayleighDamping {
  std::array<int, 2> modes{1, 3};
  std::array<double, 2> zeta{0.02, 0.02};
  std::array<double, 2> omega{0.0, 0.0};  // rad/s of those modes
  double alpha = 0.0;                     // 1/s
  double beta = 0.0;                      // s
};

// The coordinates xi of a state x = [xi; xi'].
enum class StateCoordinates {
  physical,  // xi = z, the reduced coordinates (T = I)
  modal,     // z = T xi, T the M-orthonormal modes, the rigid-body ones first
};

// x' = A x + B u, y = C x + D u, with x = [xi; xi'] and z = T xi (z the
// reduced coordinates), u the forces (moments) at the interface DOFs and
// y = [interface displacements; interface velocities].
struct StateSpace {
  Eigen::MatrixXd A, B, C, D;
  Eigen::MatrixXd T;  // n x n
  StateCoordinates coordinates = StateCoordinates::physical;
  int rigid_body_modes = 0;  // modal: the leading coordinates whose A block is exactly [0 I; 0 0]
};

const char* to_string(StateCoordinates c);  // "physical", "modal"
std::optional<StateCoordinates> parse_state_coordinates(const std::string& s);

struct FrequencyCheck {
  int mode = 0;             // 1-based mode of the full model
  double full_hz = 0.0;
  double reduced_hz = 0.0;  // the reduced model's mode of the same index
  double error_percent = 0.0;  // 100 (reduced - full) / full; 0 for rigid-body pairs
  double mac = 0.0;         // MAC of full mode and expanded reduced mode (subspace MAC over a cluster of equal frequencies)
  // The reduced mode whose expanded shape matches the full mode best (1-based)
  // and that MAC: when a reduction misses a mode, the pairing by index shifts
  // and this is the pair to compare.
  int matched_mode = 0;
  double matched_mac = 0.0;
};

// The checks that ship with every reduction.
struct ReductionChecks {
  std::vector<FrequencyCheck> frequencies;  // first N modes of the full model
  // Modal assurance criterion, full modes (rows) against the expanded reduced
  // modes (columns), on the full free DOFs:
  // MAC_ij = (phi_i' psi_j)^2 / ((phi_i' phi_i) (psi_j' psi_j)).
  Eigen::MatrixXd mac;
  int rigid_body_modes_full = 0;     // eigenvalues below the rigid-body threshold
  int rigid_body_modes_reduced = 0;
  // max_k ||K_r r_k|| / (||K_r|| ||r_k||) over the six rigid motions r_k of
  // the interface DOFs (modal coordinates zero); free-free frames only.
  double rigid_body_residual = 0.0;
  fe::MassProperties mass_full;
  fe::MassProperties mass_reduced;  // from r' M_r r, the rigid motions as above
  bool mass_comparable = false;      // true for free-free frames, where T r is the exact rigid motion
  // Static exactness of the interface flexibility under unit loads at every
  // interface DOF: max |G_reduced - G_full| / max |G_full| (for a floating
  // frame, held isostatically at interface DOFs, named in static_support).
  double static_flexibility_error = 0.0;
  std::vector<InterfaceDof> static_support;
  // The reduced model's own modes (Hz) and the damping ratio each ends up
  // with, phi' C phi / (2 omega) for M_r-normalized phi; rigid-body modes
  // report 0 (the mass-proportional part of C acts on the elastic subspace
  // only, see RayleighDamping).
  Eigen::VectorXd reduced_frequencies_hz;
  Eigen::VectorXd damping_ratios;
};

struct ReducedFrame {
  std::string name;  // the model's name
  ReductionMethod method = ReductionMethod::guyan;
  FrameSupport support = FrameSupport::grounded;
  std::optional<fe::NodeId> reference_node;  // FrameSupport::reference_node only
  InterfaceDofs retained = InterfaceDofs::translations;
  std::string interface_set;                  // name of the node set
  std::vector<InterfaceNode> interface_nodes;  // in set order
  std::vector<InterfaceDof> interface_dofs;    // the first rows of K, M, C
  // Fixed-interface modes kept (Craig-Bampton): count and frequencies (Hz).
  int mode_count = 0;
  Eigen::VectorXd mode_frequencies_hz;
  Eigen::MatrixXd K, M, C;  // (interface DOFs + modes)^2, symmetric
  RayleighDamping damping;
  StateSpace state_space;
  ReductionChecks checks;
  long full_free_dofs = 0;  // size of the full model that was reduced

  Eigen::Index coordinate_count() const { return K.rows(); }
  Eigen::Index interface_dof_count() const { return static_cast<Eigen::Index>(interface_dofs.size()); }
};

}  // namespace rigflex::reduction
