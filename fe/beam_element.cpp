#include "fe/beam_element.hpp"

#include <cmath>

namespace rigflex::fe {
namespace {

using Mat4 = Eigen::Matrix4d;

// Shear-flexibility ratio phi = 12 E I / (G As L^2); zero when shear-rigid.
double shear_ratio(const BeamProperties& p, double I, double shear_area, double L) {
  if (p.theory == BeamTheory::EulerBernoulli || shear_area <= 0.0) return 0.0;
  return 12.0 * p.E * I / (p.G * shear_area * L * L);
}

// Bending in the x-y plane, DOFs (v1, rz1, v2, rz2) with rz = dv/dx in the
// slender limit. Exact for a Timoshenko beam under end loads (Przemieniecki).
Mat4 bending_stiffness(double EI, double L, double phi) {
  Mat4 k;
  const double L2 = L * L;
  k << 12, 6 * L, -12, 6 * L,                          //
      6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2,  //
      -12, -6 * L, 12, -6 * L,                         //
      6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2;
  return EI / ((1.0 + phi) * L * L2) * k;
}

// Consistent mass of the same interpolation: translational plus rotary
// inertia parts (Friedman & Kosmatka 1993 / Przemieniecki).
Mat4 bending_mass(double rhoA, double rhoI, double L, double phi) {
  const double p = phi, p2 = phi * phi, L2 = L * L;
  const double m11 = 13.0 / 35 + 7.0 / 10 * p + 1.0 / 3 * p2;
  const double m12 = (11.0 / 210 + 11.0 / 120 * p + 1.0 / 24 * p2) * L;
  const double m13 = 9.0 / 70 + 3.0 / 10 * p + 1.0 / 6 * p2;
  const double m14 = -(13.0 / 420 + 3.0 / 40 * p + 1.0 / 24 * p2) * L;
  const double m22 = (1.0 / 105 + 1.0 / 60 * p + 1.0 / 120 * p2) * L2;
  const double m24 = -(1.0 / 140 + 1.0 / 60 * p + 1.0 / 120 * p2) * L2;
  Mat4 mt;
  mt << m11, m12, m13, m14,  //
      m12, m22, -m14, m24,   //
      m13, -m14, m11, -m12,  //
      m14, m24, -m12, m22;
  const double r11 = 6.0 / 5;
  const double r12 = (1.0 / 10 - 1.0 / 2 * p) * L;
  const double r22 = (2.0 / 15 + 1.0 / 6 * p + 1.0 / 3 * p2) * L2;
  const double r24 = (-1.0 / 30 - 1.0 / 6 * p + 1.0 / 6 * p2) * L2;
  Mat4 mr;
  mr << r11, r12, -r11, r12,  //
      r12, r22, -r12, r24,    //
      -r11, -r12, r11, -r12,  //
      r12, r24, -r12, r22;
  const double d = (1.0 + phi) * (1.0 + phi);
  return rhoA * L / d * mt + rhoI / (d * L) * mr;
}

void scatter(Eigen::MatrixXd& target, const Mat4& block, const std::array<int, 4>& idx, double sign_w) {
  // sign_w flips the rotations of the x-z plane, where ry = -dw/dx.
  const std::array<double, 4> s{1.0, sign_w, 1.0, sign_w};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) target(idx[i], idx[j]) += s[i] * s[j] * block(i, j);
}

void add_pair(Eigen::MatrixXd& target, int i, int j, double diag, double off) {
  target(i, i) += diag;
  target(j, j) += diag;
  target(i, j) += off;
  target(j, i) += off;
}

}  // namespace

Eigen::Matrix3d beam_local_axes(const Vec3& x1, const Vec3& x2, const std::optional<Vec3>& orientation) {
  const Vec3 ex = (x2 - x1).normalized();
  Vec3 up = Vec3::UnitZ();
  if (orientation) {
    up = orientation->normalized();
  } else if (std::abs(ex.dot(up)) > std::cos(M_PI / 180.0)) {
    up = Vec3::UnitX();
  }
  const Vec3 ey = up.cross(ex).normalized();
  const Vec3 ez = ex.cross(ey);
  Eigen::Matrix3d R;
  R.row(0) = ex;
  R.row(1) = ey;
  R.row(2) = ez;
  return R;
}

ElementMatrices beam_local_matrices(double L, const BeamProperties& p) {
  const SectionProperties& s = p.section;
  ElementMatrices e{Eigen::MatrixXd::Zero(12, 12), Eigen::MatrixXd::Zero(12, 12)};
  const double phi_y = shear_ratio(p, s.Iz, s.shear_area_y, L);  // deflection along y
  const double phi_z = shear_ratio(p, s.Iy, s.shear_area_z, L);  // deflection along z

  add_pair(e.K, 0, 6, p.E * s.A / L, -p.E * s.A / L);
  add_pair(e.K, 3, 9, p.G * s.J / L, -p.G * s.J / L);
  scatter(e.K, bending_stiffness(p.E * s.Iz, L, phi_y), {1, 5, 7, 11}, 1.0);
  scatter(e.K, bending_stiffness(p.E * s.Iy, L, phi_z), {2, 4, 8, 10}, -1.0);

  const double rhoA = p.rho * s.A;
  const double rhoIy = p.rotary_inertia ? p.rho * s.Iy : 0.0, rhoIz = p.rotary_inertia ? p.rho * s.Iz : 0.0;
  switch (p.mass) {
    case MassKind::Consistent:
      add_pair(e.M, 0, 6, rhoA * L / 3.0, rhoA * L / 6.0);
      add_pair(e.M, 3, 9, p.rho * s.Ip() * L / 3.0, p.rho * s.Ip() * L / 6.0);
      scatter(e.M, bending_mass(rhoA, rhoIz, L, phi_y), {1, 5, 7, 11}, 1.0);
      scatter(e.M, bending_mass(rhoA, rhoIy, L, phi_z), {2, 4, 8, 10}, -1.0);
      break;
    case MassKind::Lumped: {
      // Half the member to each node, with the rotary inertia of half the
      // member's slices; no L^2 term, so rotations stay light.
      const std::array<double, 6> m{rhoA * L / 2, rhoA * L / 2, rhoA * L / 2, p.rho * s.Ip() * L / 2,
                                    rhoIy * L / 2, rhoIz * L / 2};
      for (int n = 0; n < 2; ++n)
        for (int d = 0; d < 6; ++d) e.M(6 * n + d, 6 * n + d) = m[d];
      break;
    }
    case MassKind::None:
      break;
  }
  return e;
}

ElementMatrices beam_matrices(const Vec3& x1, const Vec3& x2, const std::optional<Vec3>& orientation,
                              const BeamProperties& p) {
  const Eigen::Matrix3d R = beam_local_axes(x1, x2, orientation);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(12, 12);
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  ElementMatrices local = beam_local_matrices((x2 - x1).norm(), p);
  return {T.transpose() * local.K * T, T.transpose() * local.M * T};
}

}  // namespace rigflex::fe
