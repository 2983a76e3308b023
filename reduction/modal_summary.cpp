#include "reduction/modal_summary.hpp"

#include <cmath>
#include <numbers>

namespace rigflex::reduction {

ModalSummary summarize_modes(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& eigenvalues,
                             const Eigen::MatrixXd& vectors, const Eigen::MatrixXd& R,
                             const std::vector<bool>& translation_rows) {
  ModalSummary s;
  const Eigen::Index k = vectors.cols();
  s.frequencies_hz = eigenvalues.unaryExpr([](double l) { return std::sqrt(std::max(l, 0.0)) / (2 * std::numbers::pi); });
  const Eigen::MatrixXd MR = M * R;
  s.total_rigid_mass = (R.transpose() * MR).diagonal();
  const Eigen::MatrixXd gamma = vectors.transpose() * MR;  // participation factors, k x 6
  s.effective_mass_fraction = Eigen::MatrixXd::Zero(k, 6);
  s.modal_mass = Eigen::VectorXd::Zero(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const double mi = vectors.col(i).dot(M * vectors.col(i));
    for (int d = 0; d < 6; ++d)
      if (s.total_rigid_mass(d) > 0) s.effective_mass_fraction(i, d) = gamma(i, d) * gamma(i, d) / mi / s.total_rigid_mass(d);
    double peak = 0.0;
    for (Eigen::Index r = 0; r < vectors.rows(); ++r)
      if (translation_rows[static_cast<size_t>(r)]) peak = std::max(peak, std::abs(vectors(r, i)));
    if (peak == 0.0) peak = vectors.col(i).cwiseAbs().maxCoeff();
    s.modal_mass(i) = peak > 0 ? mi / (peak * peak) : 0.0;
  }
  return s;
}

}  // namespace rigflex::reduction
