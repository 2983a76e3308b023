#pragma once
// Per-mode quantities a structural engineer reads off a modal analysis.
#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace rigflex::reduction {

struct ModalSummary {
  Eigen::VectorXd frequencies_hz;
  // Generalized mass with each shape scaled to a largest translation of 1.
  Eigen::VectorXd modal_mass;
  // modes x 6: effective mass in each rigid direction (TX TY TZ RX RY RZ)
  // divided by the total mass (or inertia) in that direction.
  Eigen::MatrixXd effective_mass_fraction;
  Eigen::VectorXd total_rigid_mass;  // 6: diag of R' M R
};

// vectors: M-orthonormal columns; R: rigid-body modes on the same DOFs;
// translation_rows: which rows are translations (for the max-scaling).
ModalSummary summarize_modes(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& eigenvalues,
                             const Eigen::MatrixXd& vectors, const Eigen::MatrixXd& R,
                             const std::vector<bool>& translation_rows);

}  // namespace rigflex::reduction
