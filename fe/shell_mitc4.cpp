// 4-node flat shell: MITC4 plate bending (Bathe & Dvorkin 1985) +
// incompatible-mode membrane (QM6, Taylor, Beresford & Wilson 1976) +
// drilling stabilization, formed on the element projected onto its mean plane.
#include <stdexcept>

#include "fe/shell_common.hpp"
#include "fe/shell_element.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_detail;

// Named: the two shells' helpers share their names (one unity-build source may hold both).
namespace mitc4 {

// Membrane and drilling. Bilinear membrane enriched with the bubbles
// (1 - xi^2), (1 - eta^2) in u and v, condensed out: the plain bilinear
// element locks in in-plane bending (parasitic shear), which matters for
// the webs of box girders meshed one or two elements deep. The bubble
// derivatives use the centre Jacobian scaled by det J0 / det J, so that they
// integrate to zero over any quadrilateral and the element passes the
// constant-strain patch test. The drilling penalty's omega includes the
// bubbles, so pure in-plane bending costs no drilling energy.
MatrixXd membrane_drilling_stiffness(const LocalFrame& f, const ShellProperties& p) {
  const Matrix3d C = membrane_rigidity(p);
  const double Gd = drilling_modulus(p);
  const Shape s0 = shape_q4(0.0, 0.0);
  const Matrix2d J0 = jacobian(s0, f.xy);
  const double det0 = checked_det(J0);
  const Matrix2d J0inv = J0.inverse();

  MatrixXd Kcc = MatrixXd::Zero(24, 24), Kci = MatrixXd::Zero(24, 4), Kii = MatrixXd::Zero(4, 4);
  for (const GaussPoint& g : gauss_rule(2)) {
    const Shape s = shape_q4(g.xi, g.eta);
    const Matrix2d J = jacobian(s, f.xy);
    const double det = checked_det(J);
    const Eigen::MatrixX2d dNxy = cartesian_derivatives(s, J);
    const MatrixXd Bc = membrane_B(dNxy);
    const RowVectorXd dc = drilling_row(s, dNxy);
    // Cartesian gradients of the two bubbles (columns), incompatible-mode form.
    Matrix2d ref;
    ref << -2.0 * g.xi, 0.0, 0.0, -2.0 * g.eta;
    const Matrix2d grad = det0 / det * J0inv * ref;
    MatrixXd Bi = MatrixXd::Zero(3, 4);  // internal DOFs: a_u1, a_u2, a_v1, a_v2
    RowVectorXd di = RowVectorXd::Zero(4);
    for (int k = 0; k < 2; ++k) {
      Bi(0, k) = grad(0, k);
      Bi(2, k) = grad(1, k);
      Bi(1, 2 + k) = grad(1, k);
      Bi(2, 2 + k) = grad(0, k);
      di(k) = 0.5 * grad(1, k);       // -omega from u bubble: +u_y / 2
      di(2 + k) = -0.5 * grad(0, k);  // -omega from v bubble: -v_x / 2
    }
    const double w = g.weight * det;
    Kcc += w * (Bc.transpose() * C * Bc + Gd * dc.transpose() * dc);
    Kci += w * (Bc.transpose() * C * Bi + Gd * dc.transpose() * di);
    Kii += w * (Bi.transpose() * C * Bi + Gd * di.transpose() * di);
  }
  return Kcc - Kci * Kii.ldlt().solve(Kci.transpose());
}

// Covariant transverse shear strain along the reference direction `dir`
// (0: xi, 1: eta) at a tying point, as a row over the element DOFs:
// gamma_r = w_,r + beta . x_,r with beta = (ty, -tx).
RowVectorXd covariant_shear_row(const LocalFrame& f, double xi, double eta, int dir) {
  const Shape s = shape_q4(xi, eta);
  const Matrix2d J = jacobian(s, f.xy);
  RowVectorXd row = RowVectorXd::Zero(24);
  for (int i = 0; i < 4; ++i) {
    row(dof(i, kW)) = s.dN(i, dir);
    row(dof(i, kTy)) = s.N(i) * J(dir, 0);
    row(dof(i, kTx)) = -s.N(i) * J(dir, 1);
  }
  return row;
}

// MITC4: gamma_xi is tied at the mid-points of the edges eta = -1, +1 and
// interpolated linearly in eta, gamma_eta likewise from the edges xi = -1, +1.
// Along each edge the tied strain is exact for a Kirchhoff field, so the
// element neither locks in the thin limit nor gains spurious modes.
MatrixXd bending_stiffness(const LocalFrame& f, const ShellProperties& p) {
  const Matrix3d Db = bending_rigidity(p);
  const double Ds = shear_rigidity(p);
  const RowVectorXd gxi_C = covariant_shear_row(f, 0.0, -1.0, 0);
  const RowVectorXd gxi_A = covariant_shear_row(f, 0.0, 1.0, 0);
  const RowVectorXd geta_B = covariant_shear_row(f, -1.0, 0.0, 1);
  const RowVectorXd geta_D = covariant_shear_row(f, 1.0, 0.0, 1);

  MatrixXd K = MatrixXd::Zero(24, 24);
  for (const GaussPoint& g : gauss_rule(2)) {
    const Shape s = shape_q4(g.xi, g.eta);
    const Matrix2d J = jacobian(s, f.xy);
    const double w = g.weight * checked_det(J);
    const MatrixXd Bb = bending_B(cartesian_derivatives(s, J));
    MatrixXd Bcov(2, 24);
    Bcov.row(0) = 0.5 * (1.0 - g.eta) * gxi_C + 0.5 * (1.0 + g.eta) * gxi_A;
    Bcov.row(1) = 0.5 * (1.0 - g.xi) * geta_B + 0.5 * (1.0 + g.xi) * geta_D;
    // Covariant components transform like gradients: cov = J * cartesian.
    const MatrixXd Bs = J.inverse() * Bcov;
    K += w * (Bb.transpose() * Db * Bb + Ds * Bs.transpose() * Bs);
  }
  return K;
}

}  // namespace mitc4
}  // namespace

ElementMatrices shell_mitc4(const std::vector<Vec3>& x, const ShellProperties& p) {
  check_properties(p);
  if (x.size() != 4) throw std::invalid_argument("shell_mitc4: expected 4 nodes");
  const LocalFrame f = make_local_frame(x);
  const MatrixXd K = mitc4::membrane_drilling_stiffness(f, p) + mitc4::bending_stiffness(f, p);
  return to_global(K, shell_mass(f, shape_q4, 2, p), f);
}

}  // namespace rigflex::fe
