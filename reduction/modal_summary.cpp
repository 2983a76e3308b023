#include "reduction/modal_summary.hpp"

#include <cmath>
#include <cstdio>
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
  const Eigen::MatrixXd phi_MR = vectors.transpose() * MR;  // k x 6
  s.participation = Eigen::MatrixXd::Zero(k, 6);
  s.effective_mass = Eigen::MatrixXd::Zero(k, 6);
  s.effective_mass_fraction = Eigen::MatrixXd::Zero(k, 6);
  s.cumulative_fraction = Eigen::MatrixXd::Zero(k, 6);
  s.modal_mass = Eigen::VectorXd::Zero(k);
  s.translation_share = Eigen::VectorXd::Zero(k);
  s.drilling_share = Eigen::VectorXd::Zero(k);  // the shells' are run_modal_analysis's to fill
  for (Eigen::Index i = 0; i < k; ++i) {
    const Eigen::VectorXd phi = vectors.col(i);
    const double mi = phi.dot(M * phi);
    if (!(mi > 0)) continue;
    for (int d = 0; d < 6; ++d) {
      s.participation(i, d) = phi_MR(i, d) / mi;
      s.effective_mass(i, d) = phi_MR(i, d) * phi_MR(i, d) / mi;
      if (s.total_rigid_mass(d) > 0) s.effective_mass_fraction(i, d) = s.effective_mass(i, d) / s.total_rigid_mass(d);
      s.cumulative_fraction(i, d) = s.effective_mass_fraction(i, d) + (i > 0 ? s.cumulative_fraction(i - 1, d) : 0.0);
    }
    Eigen::VectorXd translation = phi;
    double peak = 0.0;
    for (Eigen::Index r = 0; r < phi.size(); ++r) {
      if (translation_rows[static_cast<size_t>(r)]) {
        peak = std::max(peak, std::abs(phi(r)));
      } else {
        translation(r) = 0.0;
      }
    }
    s.translation_share(i) = translation.dot(M * translation) / mi;
    if (peak == 0.0) peak = phi.cwiseAbs().maxCoeff();
    s.modal_mass(i) = peak > 0 ? mi / (peak * peak) : 0.0;
  }
  return s;
}

std::vector<RotationOnlyMode> rotation_only_modes(const ModalSummary& s, double model_mass, double ratio) {
  std::vector<RotationOnlyMode> out;
  if (!(model_mass > 0)) return out;
  for (Eigen::Index i = 0; i < s.modal_mass.size(); ++i) {
    if (!(s.modal_mass(i) > ratio * model_mass)) continue;
    const double drilling = s.drilling_share(i);
    out.push_back({i, s.modal_mass(i), s.modal_mass(i) / model_mass, s.translation_share(i), drilling, drilling > 0.5});
  }
  return out;
}

std::string describe(const RotationOnlyMode& m, const ModalSummary& s) {
  char buf[520];
  if (m.drilling) {
    std::snprintf(buf, sizeof buf,
                  "mode %ld (%.6g Hz) is a shell drilling mode: %.0f %% of its kinetic energy lies in the shells' "
                  "rotations about their normals, %.2g %% in translations (modal mass %.3g kg with its largest "
                  "translation scaled to 1, %.3g x the model's mass). Drilling is no physical motion of a shell: "
                  "the mode is spurious (its stiffness is the drilling stabilization's, docs/fe-core.md)",
                  static_cast<long>(m.mode + 1), s.frequencies_hz(m.mode), 100.0 * m.drilling_share,
                  100.0 * m.translation_share, m.modal_mass, m.times_model_mass);
  } else {
    std::snprintf(buf, sizeof buf,
                  "mode %ld (%.6g Hz) moves almost only rotations (%.2g %% of its kinetic energy in translations): "
                  "a beam line's torsion or a point's rotary inertia; its modal mass with the largest translation "
                  "scaled to 1 (%.3g kg, %.3g x the model's mass) is no mass to compare",
                  static_cast<long>(m.mode + 1), s.frequencies_hz(m.mode), 100.0 * m.translation_share, m.modal_mass,
                  m.times_model_mass);
  }
  return buf;
}

}  // namespace rigflex::reduction
