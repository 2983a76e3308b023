// 8-node flat shell: serendipity membrane (3x3 Gauss) + MITC9 plate bending
// (its centre kept or condensed) + drilling stabilization, formed on the
// element projected onto its mean plane.
//
// Why not the serendipity plate with selective (2x2 shear) integration:
// on a non-parallelogram element the 8-node deflection field cannot
// represent a quadratic w (x^2 of a bilinear map has a xi^2 eta^2 term), so
// the Kirchhoff constraints cannot all be met and the element locks in the
// thin limit (MacNeal-Harder patch, L/t = 2400: 125 % error in the constant-
// curvature state). The bending field here is therefore the 9-node
// Lagrangian one, which contains every quadratic on any straight-sided
// quadrilateral, with the MITC9 assumed covariant shear strains (Bucalem &
// Bathe 1993: gamma_r tied at r = +-1/sqrt(3), s = 0, +-sqrt(3/5), linear in
// r and quadratic in s; gamma_s likewise), which has no spurious modes and
// showed no shear locking here (clamped plate down to t/L = 1e-4, the
// MacNeal-Harder patch at L/t = 2400). The centre's w, tx, ty are either
// kept as three coordinates of the element's own (shell_quad8_with_centre:
// the default, on a node add_shell_centres() generates) or condensed
// statically (shell_quad8: lumped mass, and models built without centres).
// Kept, they are hierarchical - the centre's values above the 8 nodes'
// serendipity interpolation - so rigid motions leave them at zero. The
// consistent mass of the bending DOFs is that of the same 9-node field
// (T' M9 T, T the map from the element's DOFs to the field's): the
// stiffness and the mass then describe one displacement field. With the
// serendipity mass instead (the centre's motion left out of the inertia),
// the rhombic plates' frequencies came out low: NAFEMS FV22 (t = 1 m) at
// its 10 x 10 mesh -0.35..-2.17 % against the plate's exact solution. The
// static condensation leaves the centre's own dynamics out: an error of
// order (omega h / c_shear)^2 that makes thick plates converge as h^2
// (FV22 +0.12..+0.88 %, Test 21 up to +0.99 % at 8 x 8); with the centre
// kept, +0.05..+0.39 % and +0.28 %, converging as h^4
// (tests/verification/test_distorted_meshes.cpp, test_square_plates.cpp).
// Lumped mass stays the serendipity HRZ diagonal.
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "fe/shell_common.hpp"
#include "fe/shell_element.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_detail;

// Named: the two shells' helpers share their names (one unity-build source may hold both).
namespace quad8 {

// Membrane and drilling penalty (shell_common.cpp), both with the full 3x3
// rule: it integrates the quadratic fields and sees all 8 nodal tz patterns.
MatrixXd membrane_drilling_stiffness(const LocalFrame& f, const ShellProperties& p) {
  const Matrix3d C = membrane_rigidity(p);
  const double Gd = drilling_modulus(p);
  MatrixXd K = MatrixXd::Zero(48, 48);
  for (const GaussPoint& g : gauss_rule(3)) {
    const Shape s = shape_q8(g.xi, g.eta);
    const Matrix2d J = jacobian(s, f.xy);
    const Eigen::MatrixX2d dNxy = cartesian_derivatives(s, J);
    const MatrixXd B = membrane_B(dNxy);
    const RowVectorXd d = drilling_row(s, dNxy);
    K += g.weight * checked_det(J) * (B.transpose() * C * B + Gd * d.transpose() * d);
  }
  return K;
}

// 9-node Lagrangian shape functions; node 9 (index 8) at the centre.
Shape shape_q9(double xi, double eta) {
  auto l = [](double r, double c) { return c < 0 ? 0.5 * r * (r - 1) : c > 0 ? 0.5 * r * (r + 1) : 1 - r * r; };
  auto dl = [](double r, double c) { return c < 0 ? r - 0.5 : c > 0 ? r + 0.5 : -2 * r; };
  Shape s;
  s.N.resize(9);
  s.dN.resize(9, 2);
  for (int i = 0; i < 9; ++i) {
    const Vector2d c = node_reference_coords(i);
    s.N(i) = l(xi, c.x()) * l(eta, c.y());
    s.dN(i, 0) = dl(xi, c.x()) * l(eta, c.y());
    s.dN(i, 1) = l(xi, c.x()) * dl(eta, c.y());
  }
  return s;
}

// The geometry stays the 8-node map; the centre node sits at its image of
// (0, 0), so straight-sided elements get exact quadratic deflections.
Matrix2d geometry_jacobian(const LocalFrame& f, double xi, double eta) { return jacobian(shape_q8(xi, eta), f.xy); }

constexpr int kFull = 54;  // 9 nodes x 6 local DOFs

// Covariant transverse shear strain along reference direction `dir` at a
// tying point: gamma_r = w_,r + beta . x_,r, beta = (ty, -tx).
RowVectorXd covariant_shear_row(const LocalFrame& f, double xi, double eta, int dir) {
  const Shape s = shape_q9(xi, eta);
  const Matrix2d J = geometry_jacobian(f, xi, eta);
  RowVectorXd row = RowVectorXd::Zero(kFull);
  for (int i = 0; i < 9; ++i) {
    row(dof(i, kW)) = s.dN(i, dir);
    row(dof(i, kTy)) = s.N(i) * J(dir, 0);
    row(dof(i, kTx)) = -s.N(i) * J(dir, 1);
  }
  return row;
}

// MITC9 assumed shear: gamma_xi from the 2 x 3 points (+-a, {-b, 0, b}),
// Lagrange-interpolated linearly in xi and quadratically in eta; gamma_eta
// symmetrically.
class Mitc9Shear {
 public:
  explicit Mitc9Shear(const LocalFrame& f) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j) {
        xi_rows_[i][j] = covariant_shear_row(f, kA[i], kB[j], 0);
        eta_rows_[i][j] = covariant_shear_row(f, kB[j], kA[i], 1);
      }
  }
  // Rows [gamma_xi; gamma_eta] at a point.
  MatrixXd covariant(double xi, double eta) const {
    MatrixXd B = MatrixXd::Zero(2, kFull);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j) {
        B.row(0) += linear(xi, i) * quadratic(eta, j) * xi_rows_[i][j];
        B.row(1) += linear(eta, i) * quadratic(xi, j) * eta_rows_[i][j];
      }
    return B;
  }

 private:
  static constexpr double kA[2] = {-0.57735026918962576, 0.57735026918962576};     // -+1/sqrt(3)
  static constexpr double kB[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};  // -+sqrt(3/5)
  static double linear(double r, int i) { return 0.5 * (1.0 + r / kA[i]); }
  static double quadratic(double r, int j) {
    const double b = kB[2];
    if (j == 1) return 1.0 - r * r / (b * b);
    return 0.5 * r * (r + (j == 0 ? -b : b)) / (b * b);
  }
  RowVectorXd xi_rows_[2][3], eta_rows_[2][3];
};

// Plate stiffness of the 9-node field on its 54 local DOFs (the centre's
// only through w, tx, ty).
MatrixXd bending_stiffness(const LocalFrame& f, const ShellProperties& p) {
  const Matrix3d Db = bending_rigidity(p);
  const double Ds = shear_rigidity(p);
  const Mitc9Shear shear(f);
  MatrixXd K = MatrixXd::Zero(kFull, kFull);
  for (const GaussPoint& g : gauss_rule(3)) {
    const Matrix2d J = geometry_jacobian(f, g.xi, g.eta);
    const double w = g.weight * checked_det(J);
    const MatrixXd Bb = bending_B(cartesian_derivatives(shape_q9(g.xi, g.eta), J));
    const MatrixXd Bs = J.inverse() * shear.covariant(g.xi, g.eta);
    K += w * (Bb.transpose() * Db * Bb + Ds * Bs.transpose() * Bs);
  }
  return K;
}

const std::array<int, 3> kCentre{dof(8, kW), dof(8, kTx), dof(8, kTy)};

// The 9-node field's 54 DOFs from the element's: the 48 of the 8 nodes, the
// centre's w, tx, ty given by `centre` (3 x 48) plus, when `amplitudes`, the
// element's own three coordinates (columns 48..50).
MatrixXd field_map(const MatrixXd& centre, bool amplitudes) {
  MatrixXd T = MatrixXd::Zero(kFull, amplitudes ? 51 : 48);
  T.topLeftCorner(48, 48).setIdentity();
  for (size_t a = 0; a < 3; ++a) {
    T.row(kCentre[a]).head(48) = centre.row(static_cast<Eigen::Index>(a));
    if (amplitudes) T(kCentre[a], 48 + static_cast<Eigen::Index>(a)) = 1.0;
  }
  return T;
}

// Static condensation: the centre as the stiffness places it for the
// boundary nodes' motion, with no load of its own.
MatrixXd condensed_centre(const MatrixXd& K) {
  MatrixXd Kbi(48, 3), Kii(3, 3);
  for (size_t a = 0; a < 3; ++a) {
    Kbi.col(static_cast<Eigen::Index>(a)) = K.col(kCentre[a]).head(48);
    for (size_t b = 0; b < 3; ++b)
      Kii(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = K(kCentre[a], kCentre[b]);
  }
  return -Kii.ldlt().solve(Kbi.transpose());
}

// Hierarchical centre: the serendipity interpolation of the 8 nodes' w, tx,
// ty at (0, 0) (corners -1/4, mid-sides +1/2), which any rigid motion meets
// exactly (the map is isoparametric), so the amplitudes on top are pure
// deformation and vanish in rigid motion, as mass_properties assumes.
MatrixXd interpolated_centre() {
  const Shape s = shape_q8(0.0, 0.0);
  MatrixXd C = MatrixXd::Zero(3, 48);
  const std::array<int, 3> local{kW, kTx, kTy};
  for (int i = 0; i < 8; ++i)
    for (size_t a = 0; a < 3; ++a) C(static_cast<Eigen::Index>(a), dof(i, local[a])) = s.N(i);
  return C;
}

// Consistent mass of w, tx, ty (translation rho t, rotary inertia
// rho t^3/12 about the in-plane axes, as shell_mass) of the 9-node field on
// its 54 DOFs.
MatrixXd bending_mass(const LocalFrame& f, const ShellProperties& p) {
  MatrixXd G = MatrixXd::Zero(9, 9);
  for (const GaussPoint& g : gauss_rule(3)) {
    const Shape s = shape_q9(g.xi, g.eta);
    G += g.weight * checked_det(geometry_jacobian(f, g.xi, g.eta)) * s.N * s.N.transpose();
  }
  const double translational = p.rho * p.thickness;
  const double rotary = p.rho * std::pow(p.thickness, 3) / 12.0;
  MatrixXd M = MatrixXd::Zero(kFull, kFull);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) {
      M(dof(i, kW), dof(j, kW)) = translational * G(i, j);
      for (int a : {kTx, kTy}) M(dof(i, a), dof(j, a)) = rotary * G(i, j);
    }
  return M;
}

// Both variants: membrane and drilling on the 48 node DOFs, the 9-node plate
// through T (54 x 48 condensed, 54 x 51 with the centre's amplitudes).
ElementMatrices assemble(const std::vector<Vec3>& x, const ShellProperties& p, bool amplitudes) {
  check_properties(p);
  if (x.size() != 8) throw std::invalid_argument("shell_quad8: expected 8 nodes");
  const LocalFrame f = make_local_frame(x);
  const MatrixXd Kb = bending_stiffness(f, p);
  const MatrixXd T = field_map(amplitudes ? interpolated_centre() : condensed_centre(Kb), amplitudes);
  const Eigen::Index n = T.cols();
  MatrixXd K = T.transpose() * Kb * T;
  K.topLeftCorner(48, 48) += membrane_drilling_stiffness(f, p);
  MatrixXd M = MatrixXd::Zero(n, n);
  M.topLeftCorner(48, 48) = shell_mass(f, shape_q8, 3, p);
  if (p.mass == MassKind::Consistent && p.rho != 0.0) {
    // The membrane's u, v keep the serendipity mass; w, tx, ty take the
    // 9-node field's, which couples them to each other too.
    const MatrixXd Mb = T.transpose() * bending_mass(f, p) * T;
    std::vector<Eigen::Index> bending;
    for (int i = 0; i < 8; ++i)
      for (int a : {kW, kTx, kTy}) bending.push_back(dof(i, a));
    for (Eigen::Index c = 48; c < n; ++c) bending.push_back(c);
    for (Eigen::Index r : bending)
      for (Eigen::Index c : bending) M(r, c) = Mb(r, c);
  }
  return to_global(K, M, f);
}

}  // namespace quad8
}  // namespace

ElementMatrices shell_quad8(const std::vector<Vec3>& x, const ShellProperties& p) {
  return quad8::assemble(x, p, false);
}

ElementMatrices shell_quad8_with_centre(const std::vector<Vec3>& x, const ShellProperties& p) {
  if (p.mass != MassKind::Consistent)
    throw std::invalid_argument("shell_quad8_with_centre: the centre's coordinates need the consistent mass");
  return quad8::assemble(x, p, true);
}

}  // namespace rigflex::fe
