#pragma once
// Per-mode quantities a structural engineer reads off a modal analysis:
// where each mode's mass lies (effective masses, participation factors,
// their running sums) and which modes carry almost none of it in
// translation - a sign of a rotation-only mode, physical (a beam line's
// torsion, a point's rotary inertia) or spurious (a shell's drilling
// rotation).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

namespace rigflex::reduction {

struct ModalSummary {
  Eigen::VectorXd frequencies_hz;
  // Generalized mass with each shape scaled to a largest translation of 1.
  Eigen::VectorXd modal_mass;
  // modes x 6, the rigid directions TX TY TZ RX RY RZ (rotations about the
  // CoG): participation factor phi' M r / phi' M phi; effective mass
  // (phi' M r)^2 / phi' M phi in kg and kg m^2; that divided by the total
  // mass (or inertia) in the direction; the running sum of the fractions
  // over the modes so far (over all modes of a free model it reaches 1).
  Eigen::MatrixXd participation;
  Eigen::MatrixXd effective_mass;
  Eigen::MatrixXd effective_mass_fraction;
  Eigen::MatrixXd cumulative_fraction;
  // Share of each mode's kinetic energy phi' M phi in its translations
  // alone (the rotations' rows zeroed); near 0 for a rotation-only mode.
  // Where the consistent mass couples translations to rotations (beams,
  // 8-node shells) it can pass 1 slightly on a coarse mesh.
  Eigen::VectorXd translation_share;
  // Share of it in the shells' drilling rotations (each shell node's
  // rotation about its mean normal). Zeros from summarize_modes, which
  // knows no shells; run_modal_analysis fills it (shell_drilling_share).
  Eigen::VectorXd drilling_share;
  Eigen::VectorXd total_rigid_mass;  // 6: diag of R' M R
};

// vectors: M-orthogonal columns; R: rigid-body modes on the same DOFs;
// translation_rows: which rows are translations (for the max-scaling).
ModalSummary summarize_modes(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& eigenvalues,
                             const Eigen::MatrixXd& vectors, const Eigen::MatrixXd& R,
                             const std::vector<bool>& translation_rows);

// A mode whose modal mass (largest translation 1) exceeds `ratio` x the
// model's mass. With the translations bounded by 1 their kinetic energy is
// at most about 3 x the model's mass (each direction's share at most the
// mass), so such a mode moves almost only rotations: at the default
// 100 x, 97 % or more of its kinetic energy lies in rotation DOFs. A beam
// line's torsion or a point's rotary inertia is physical (`drilling` false:
// a note); one whose kinetic energy lies mostly (over half) in the shells'
// drilling rotations is spurious (a warning).
struct RotationOnlyMode {
  Eigen::Index mode = 0;  // 0-based
  double modal_mass = 0;
  double times_model_mass = 0;
  double translation_share = 0;
  double drilling_share = 0;
  bool drilling = false;
};
std::vector<RotationOnlyMode> rotation_only_modes(const ModalSummary& s, double model_mass, double ratio = 100.0);
// One line for a user: the mode, its numbers, and what such a mode is.
std::string describe(const RotationOnlyMode& m, const ModalSummary& s);

}  // namespace rigflex::reduction
