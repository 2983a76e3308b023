// Element-level checks of the MITC4 and Quad8 flat shells: symmetry, rigid
// modes, mass totals, frame independence and the geometry checks.
#include <array>

#include "fe/error.hpp"
#include "test_shell_helpers.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_test;

// A distorted (non-parallelogram) quadrilateral with unit-order size.
std::vector<Vec3> distorted_corners() { return {{0.0, 0.0, 0.0}, {1.2, 0.1, 0.0}, {1.1, 0.9, 0.0}, {-0.1, 1.0, 0.0}}; }

// Shoelace area of the corner quadrilateral in its own plane.
double corner_area(const std::vector<Vec3>& x) { return 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm(); }

std::vector<Vec3> placed(std::vector<Vec3> x, bool rotate) {
  if (rotate)
    for (Vec3& v : x) v = general_rotation() * v + Vec3(3.0, -2.0, 5.0);
  return x;
}

ShellProperties props(double t, MassKind mass = MassKind::Consistent) { return {200e9, 0.3, 8000.0, t, mass}; }

struct Case {
  bool quadratic;
  bool rotated;
  double thickness;
};

class ShellElementCase : public ::testing::TestWithParam<Case> {
 protected:
  std::vector<Vec3> nodes() const {
    const std::vector<Vec3> c = distorted_corners();
    return placed(GetParam().quadratic ? with_midsides(c) : c, GetParam().rotated);
  }
};

// K and M are symmetrized explicitly, so exact equality is expected.
TEST_P(ShellElementCase, MatricesAreSymmetric) {
  const ElementMatrices e = element(nodes(), props(GetParam().thickness));
  const auto n = static_cast<Eigen::Index>(6 * nodes().size());
  ASSERT_EQ(e.K.rows(), n);
  ASSERT_EQ(e.M.rows(), n);
  EXPECT_EQ((e.K - e.K.transpose()).norm(), 0.0);
  EXPECT_EQ((e.M - e.M.transpose()).norm(), 0.0);
}

// Exactly six zero eigenvalues. After Jacobi scaling the rigid modes sit at
// round-off (~1e-15) and the softest deformation mode at ~(t/L)^2 (bending
// vs shear), >= 1e-7 here; 1e-10 separates them with margin both ways.
TEST_P(ShellElementCase, FreeElementHasExactlySixZeroModes) {
  const ElementMatrices e = element(nodes(), props(GetParam().thickness));
  const Eigen::VectorXd ev = scaled_eigenvalues(e.K);
  const double top = ev(ev.size() - 1);
  EXPECT_EQ(count_zero_modes(e.K, 1e-10), 6);
  EXPECT_GT(ev(6), 1e-8 * top) << "7th eigenvalue is (nearly) zero: spurious mode";
}

// Rigid translations and rotations about an arbitrary point give no nodal
// force; the bound is round-off relative to |K| |u|.
TEST_P(ShellElementCase, RigidMotionsProduceNoForce) {
  const std::vector<Vec3> x = nodes();
  const ElementMatrices e = element(x, props(GetParam().thickness));
  const Vec3 c(0.3, -0.7, 1.1);
  for (int k = 0; k < 6; ++k) {
    Vec3 t = Vec3::Zero(), r = Vec3::Zero();
    (k < 3 ? t : r)(k % 3) = 1.0;
    const Eigen::VectorXd u = rigid_motion(x, t, r, c);
    EXPECT_LT((e.K * u).norm(), 1e-12 * e.K.norm() * u.norm()) << "rigid motion " << k;
  }
}

// Total translational mass rho t A in every direction; rotary inertia
// rho t^3/12 A about the in-plane axes and none about the normal (a normal
// fibre has no inertia about its own axis), so about global axis d it is
// rho t^3/12 A (1 - n_d^2). Consistent and lumped (exact quadrature of
// polynomials: round-off tolerance). The rotary totals hold where the
// nodes' rotations are interpolated as they stand; the 8-node element's
// consistent mass follows its condensed centre, which does not stay at the
// nodes' common rotation unless the motion is rigid (checked below).
TEST_P(ShellElementCase, MassTotals) {
  const std::vector<Vec3> x = nodes();
  const double t = GetParam().thickness;
  const double A = corner_area(x);
  const Vec3 normal = (x[2] - x[0]).cross(x[3] - x[1]).normalized();
  for (MassKind kind : {MassKind::Consistent, MassKind::Lumped}) {
    const ElementMatrices e = element(x, props(t, kind));
    for (int d = 0; d < 6; ++d) {
      if (d >= 3 && kind == MassKind::Consistent && GetParam().quadratic) continue;
      Eigen::VectorXd u = Eigen::VectorXd::Zero(e.M.rows());
      for (size_t i = 0; i < x.size(); ++i) u(6 * static_cast<Eigen::Index>(i) + d) = 1.0;
      const double rotary = t * t / 12.0 * (1.0 - normal(d % 3) * normal(d % 3));
      const double expected = 8000.0 * t * A * (d < 3 ? 1.0 : rotary);
      EXPECT_NEAR(u.dot(e.M * u), expected, 1e-12 * 8000.0 * t * A * (d < 3 ? 1.0 : t * t / 12.0)) << "dof " << d;
    }
    // Massless exactly along each node's drilling rotation, positive
    // definite on everything else.
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(e.M).eigenvalues();
    const auto drilling = static_cast<Eigen::Index>(x.size());
    EXPECT_LT(ev.head(drilling).cwiseAbs().maxCoeff(), 1e-14 * ev(ev.size() - 1));
    EXPECT_GT(ev(drilling), 1e-6 * 8000.0 * t * t * t / 12.0 * A / static_cast<double>(x.size()));
    for (Eigen::Index i = 0; i < drilling; ++i) {
      Eigen::VectorXd spin = Eigen::VectorXd::Zero(e.M.rows());
      spin.segment<3>(6 * i + 3) = normal;
      EXPECT_LT((e.M * spin).norm(), 1e-14 * e.M.norm()) << "node " << i;
    }
  }
  const ElementMatrices none = element(x, props(t, MassKind::None));
  EXPECT_EQ(none.M.norm(), 0.0);
}

// The consistent mass moved rigidly is the body's: Phi' M Phi over the six
// rigid motions about a point c equals the plate's rigid-body mass matrix,
// its mass, first moment and inertia tensor (membrane area inertia from the
// two triangles' closed form, plus rho t^3/12 A about the in-plane axes).
// Round-off tolerance: the rules integrate the fields exactly.
TEST_P(ShellElementCase, ConsistentMassMovedRigidlyIsTheBodys) {
  const std::vector<Vec3> x = nodes();
  const double t = GetParam().thickness, rho = 8000.0;
  const ElementMatrices e = element(x, props(t));
  const Vec3 c(0.3, -0.7, 1.1);
  Eigen::Matrix<double, Eigen::Dynamic, 6> Phi(e.M.rows(), 6);
  for (int k = 0; k < 6; ++k) {
    Vec3 v = Vec3::Zero(), r = Vec3::Zero();
    (k < 3 ? v : r)(k % 3) = 1.0;
    Phi.col(k) = rigid_motion(x, v, r, c);
  }
  // Second moments about c: a triangle's integral of d d' is A/12 (sum of
  // d_i d_i' + (sum d_i)(sum d_i)'), its first moment A (sum d_i) / 3.
  double A = 0.0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const std::array<int, 3>& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
    const Vec3 a = x[tri[0]] - c, b = x[tri[1]] - c, d = x[tri[2]] - c;
    const double area = 0.5 * (b - a).cross(d - a).norm();
    const Vec3 sum = a + b + d;
    A += area;
    first += area * sum / 3.0;
    S += area / 12.0 * (a * a.transpose() + b * b.transpose() + d * d.transpose() + sum * sum.transpose());
  }
  const Vec3 n = (x[2] - x[0]).cross(x[3] - x[1]).normalized();
  Eigen::Matrix<double, 6, 6> expected = Eigen::Matrix<double, 6, 6>::Zero();
  expected.topLeftCorner<3, 3>() = rho * t * A * Eigen::Matrix3d::Identity();
  // Translation e_i against rotation e_j: integral of e_i . (e_j x d).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      expected(i, 3 + j) = expected(3 + j, i) = rho * t * Vec3::Unit(i).dot(Vec3::Unit(j).cross(first));
  expected.bottomRightCorner<3, 3>() = rho * t * (S.trace() * Eigen::Matrix3d::Identity() - S) +
                                       rho * t * t * t / 12.0 * A * (Eigen::Matrix3d::Identity() - n * n.transpose());
  const Eigen::Matrix<double, 6, 6> got = Phi.transpose() * e.M * Phi;
  EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm()) << "got\n" << got << "\nexpected\n" << expected;
}

// Lumped mass couples no two nodes and no translation to a rotation; the
// translations are diagonal with positive entries (for the 8-node element
// that relies on HRZ scaling: row sums would give negative corner masses),
// the rotations of a node are c (I - n n'), c > 0: diagonal in the
// element's own axes.
TEST_P(ShellElementCase, LumpedMassIsDiagonalAndPositive) {
  const std::vector<Vec3> x = nodes();
  const ElementMatrices e = element(x, props(GetParam().thickness, MassKind::Lumped));
  const Vec3 normal = (x[2] - x[0]).cross(x[3] - x[1]).normalized();
  const double scale = e.M.diagonal().maxCoeff();
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(x.size()); ++i) {
    Eigen::MatrixXd off = e.M.middleRows(6 * i, 6);
    off.middleCols(6 * i + 3, 3).setZero();
    off.middleCols(6 * i, 3).setZero();
    EXPECT_LT(off.cwiseAbs().maxCoeff(), 1e-14 * scale) << "node " << i;
    const Eigen::Matrix3d translation = e.M.block<3, 3>(6 * i, 6 * i);
    EXPECT_LT((translation - Eigen::Matrix3d(translation.diagonal().asDiagonal())).cwiseAbs().maxCoeff(),
              1e-14 * scale);
    EXPECT_GT(translation.diagonal().minCoeff(), 0.0);
    const Eigen::Matrix3d rotation = e.M.block<3, 3>(6 * i + 3, 6 * i + 3);
    const double c = rotation.trace() / 2.0;
    EXPECT_GT(c, 0.0);
    const Eigen::Matrix3d expected = c * (Eigen::Matrix3d::Identity() - normal * normal.transpose());
    EXPECT_LT((rotation - expected).cwiseAbs().maxCoeff(), 1e-12 * c) << "node " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Shells, ShellElementCase,
                         ::testing::Values(Case{false, false, 0.05}, Case{false, true, 0.05}, Case{false, true, 1e-3},
                                           Case{true, false, 0.05}, Case{true, true, 0.05}, Case{true, true, 1e-3}),
                         [](const auto& info) {
                           const Case& c = info.param;
                           return std::string(c.quadratic ? "Quad8" : "MITC4") + (c.rotated ? "_rotated" : "_flat") +
                                  (c.thickness < 0.01 ? "_thin" : "_thick");
                         });

// The result must not depend on where the element sits or on which corner
// is numbered first: K in a rotated position equals the rotated K, and a
// cyclic renumbering gives the permuted K. Tolerance: round-off.
TEST(ShellElement, FrameIndependence) {
  for (bool quadratic : {false, true}) {
    const std::vector<Vec3> c = distorted_corners();
    const std::vector<Vec3> flat = quadratic ? with_midsides(c) : c;
    const ShellProperties p = props(0.05);
    const ElementMatrices e0 = element(flat, p);

    const Eigen::Matrix3d Q = general_rotation();
    const ElementMatrices e1 = element(placed(flat, true), p);
    const auto n = static_cast<Eigen::Index>(flat.size());
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(6 * n, 6 * n);
    for (Eigen::Index i = 0; i < 2 * n; ++i) T.block<3, 3>(3 * i, 3 * i) = Q.transpose();
    EXPECT_LT((T.transpose() * e0.K * T - e1.K).norm(), 1e-12 * e0.K.norm()) << (quadratic ? "Quad8" : "MITC4");
    EXPECT_LT((T.transpose() * e0.M * T - e1.M).norm(), 1e-12 * e0.M.norm());

    // Cyclic renumbering: corners 2 3 4 1 (and mid-sides 6 7 8 5).
    std::vector<int> perm{1, 2, 3, 0};
    if (quadratic) perm.insert(perm.end(), {5, 6, 7, 4});
    std::vector<Vec3> shifted;
    for (int k : perm) shifted.push_back(flat[static_cast<size_t>(k)]);
    const ElementMatrices e2 = element(shifted, p);
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6 * n, 6 * n);  // u_shifted = P u_original
    for (Eigen::Index i = 0; i < n; ++i) P.block<6, 6>(6 * i, 6 * perm[static_cast<size_t>(i)]).setIdentity();
    EXPECT_LT((P.transpose() * e2.K * P - e0.K).norm(), 1e-12 * e0.K.norm()) << (quadratic ? "Quad8" : "MITC4");
    EXPECT_LT((P.transpose() * e2.M * P - e0.M).norm(), 1e-12 * e0.M.norm()) << (quadratic ? "Quad8" : "MITC4");
  }
}

// Warped 4-node element (0.5 % of its size, accepted by the geometry check):
// the rigid offsets keep the six rigid modes exact.
TEST(ShellElement, WarpedElementKeepsRigidModes) {
  std::vector<Vec3> x = distorted_corners();
  const double h = 0.005;
  for (size_t i = 0; i < 4; ++i) x[i].z() = (i % 2 == 0 ? h : -h);
  EXPECT_NO_THROW(check_shell_geometry(x, "w"));
  const ElementMatrices e = shell_mitc4(placed(x, true), props(0.05));
  EXPECT_EQ(count_zero_modes(e.K), 6);
  const std::vector<Vec3> y = placed(x, true);
  for (int k = 3; k < 6; ++k) {
    Vec3 r = Vec3::Zero();
    r(k - 3) = 1.0;
    const Eigen::VectorXd u = rigid_motion(y, Vec3::Zero(), r, Vec3(1.0, 2.0, 3.0));
    EXPECT_LT((e.K * u).norm(), 1e-12 * e.K.norm() * u.norm());
  }
}

// Rotation about the normal is resisted relative to the in-plane material
// rotation: a pure nodal drilling rotation (no translation) costs energy
// (the penalty is 1e-2 G t per unit area; the bound checks it is there),
// while the same rotation with the matching in-plane field is a rigid
// motion (RigidMotionsProduceNoForce).
TEST(ShellElement, DrillingStiffnessIsActive) {
  for (bool quadratic : {false, true}) {
    const std::vector<Vec3> x = quadratic ? with_midsides(distorted_corners()) : distorted_corners();
    const ElementMatrices e = element(x, props(0.05));
    Eigen::VectorXd u = Eigen::VectorXd::Zero(e.K.rows());
    for (size_t i = 0; i < x.size(); ++i) u(6 * static_cast<Eigen::Index>(i) + 5) = 1.0;
    EXPECT_GT(u.dot(e.K * u), 1e-3 * 200e9 / 2.6 * 0.05 * corner_area(x)) << (quadratic ? "Quad8" : "MITC4");
  }
}

void expect_geometry_error(const std::vector<Vec3>& x, const std::string& what) {
  try {
    check_shell_geometry(x, "bad");
    ADD_FAILURE() << what << ": no error";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().kind, "shell") << what;
    EXPECT_EQ(e.where().id, "bad") << what;
    EXPECT_EQ(e.where().key, "nodes") << what;
  }
}

TEST(ShellGeometry, AcceptsValidElements) {
  const std::vector<Vec3> c = distorted_corners();
  EXPECT_NO_THROW(check_shell_geometry(c, "ok"));
  EXPECT_NO_THROW(check_shell_geometry(with_midsides(c), "ok"));
  EXPECT_NO_THROW(check_shell_geometry(placed(c, true), "ok"));
  // Clockwise numbering only flips the normal in 3D: accepted.
  EXPECT_NO_THROW(check_shell_geometry({c[0], c[3], c[2], c[1]}, "ok"));
}

TEST(ShellGeometry, RejectsBadElements) {
  const std::vector<Vec3> c = distorted_corners();
  expect_geometry_error({c[0], c[1], c[2], c[2]}, "coincident");
  expect_geometry_error({c[0], c[1], {0.3, 0.3, 0.0}, c[3]}, "concave");
  expect_geometry_error({c[0], c[1], c[3], c[2]}, "bow-tie");
  expect_geometry_error({c[0], {0.5, 0.5, 0.0}, {1.0, 1.0, 0.0}, c[3]}, "collinear corner");
  expect_geometry_error({c[0], c[1], c[2], c[3], {0.0, 0.0, 0.0}}, "five nodes");
  std::vector<Vec3> warped = c;
  for (size_t i = 0; i < 4; ++i) warped[i].z() = (i % 2 == 0 ? 0.02 : -0.02);
  expect_geometry_error(warped, "warped 2 %");
  // Mid-side node pulled to within 1/8 of the edge of a corner: det J < 0
  // near that corner.
  std::vector<Vec3> q = with_midsides(c);
  q[4] = c[0] + 0.1 * (c[1] - c[0]);
  expect_geometry_error(q, "mid-side node near corner");
  q = with_midsides(c);
  q[5].z() += 0.05;
  expect_geometry_error(q, "curved 8-node element");
}

TEST(ShellElement, RejectsBadPropertiesAndNodeCounts) {
  const std::vector<Vec3> c = distorted_corners();
  EXPECT_THROW(shell_mitc4(c, props(0.0)), std::invalid_argument);
  EXPECT_THROW(shell_mitc4(with_midsides(c), props(0.05)), std::invalid_argument);
  EXPECT_THROW(shell_quad8(c, props(0.05)), std::invalid_argument);
  EXPECT_THROW(shell_mitc4({c[0], c[1], c[3], c[2]}, props(0.05)), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::fe
