// The 8-node shell with its centre kept (shell_quad8_with_centre) against
// the condensed one, and the nodes that carry the centre's coordinates in a
// model (add_shell_centres, coordinate_nodes, rigid-body modes).
#include <Eigen/Eigenvalues>
#include <set>

#include "fe/error.hpp"
#include "fe/mass_properties.hpp"
#include "fe/shell_centres.hpp"
#include "test_shell_helpers.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_test;

ShellProperties props(double t, MassKind mass = MassKind::Consistent) { return {kE, kNu, kRho, t, mass}; }

// A distorted element (no two sides parallel) in a general position.
std::vector<Vec3> distorted_element() {
  std::vector<Vec3> x = with_midsides({{0.0, 0.0, 0.0}, {1.2, 0.1, 0.0}, {1.1, 0.9, 0.0}, {-0.1, 1.0, 0.0}});
  for (Vec3& v : x) v = general_rotation() * v + Vec3(3.0, -2.0, 5.0);
  return x;
}

// Eliminating the centre's three coordinates statically must give back the
// condensed element exactly: both are the same 9-node field, only the
// centre's parameters differ (a change of variables before condensing).
// Round-off tolerance relative to |K|; the thin case (t/L = 1e-3) spans six
// decades between membrane and bending terms.
TEST(ShellCentre, CondensingTheCentreGivesTheCondensedElement) {
  const std::vector<Vec3> x = distorted_element();
  for (double t : {0.05, 1e-3}) {
    const ElementMatrices kept = shell_quad8_with_centre(x, props(t));
    const ElementMatrices condensed = shell_quad8(x, props(t));
    ASSERT_EQ(kept.K.rows(), 51);
    const Eigen::MatrixXd Kbb = kept.K.topLeftCorner(48, 48), Kbi = kept.K.topRightCorner(48, 3);
    const Eigen::MatrixXd Kii = kept.K.bottomRightCorner(3, 3);
    const Eigen::MatrixXd K = Kbb - Kbi * Kii.ldlt().solve(Kbi.transpose());
    EXPECT_LT((K - condensed.K).norm(), 1e-10 * condensed.K.norm()) << "t = " << t;
    // The nodes' own mass (centre at rest) differs from the condensed one
    // only through the bending DOFs' coupling to the centre: the
    // translations' u, v blocks are the serendipity mass in both.
    EXPECT_EQ((kept.M - kept.M.transpose()).norm(), 0.0);
    EXPECT_EQ((kept.K - kept.K.transpose()).norm(), 0.0);
  }
}

// The centre's coordinates are deformation: a rigid motion of the nodes
// with the coordinates at zero costs no energy, and carries the body's mass
// matrix, the same as the condensed element's (whose centre follows
// rigidly). Exactly six zero modes on the 51 DOFs; the mass is positive
// definite on the coordinates (they move the centre: translation and
// rotary inertia).
TEST(ShellCentre, RigidMotionsLeaveTheCoordinatesAtZero) {
  const std::vector<Vec3> x = distorted_element();
  const double t = 0.05;
  const ElementMatrices kept = shell_quad8_with_centre(x, props(t));
  const ElementMatrices condensed = shell_quad8(x, props(t));
  const Vec3 c(0.3, -0.7, 1.1);
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(51, 6);
  for (int k = 0; k < 6; ++k) {
    Vec3 v = Vec3::Zero(), r = Vec3::Zero();
    (k < 3 ? v : r)(k % 3) = 1.0;
    Phi.col(k).head(48) = rigid_motion(x, v, r, c);
    EXPECT_LT((kept.K * Phi.col(k)).norm(), 1e-12 * kept.K.norm() * Phi.col(k).norm()) << "rigid motion " << k;
  }
  const Eigen::MatrixXd rigid_kept = Phi.transpose() * kept.M * Phi;
  const Eigen::MatrixXd rigid_condensed = Phi.topRows(48).transpose() * condensed.M * Phi.topRows(48);
  EXPECT_LT((rigid_kept - rigid_condensed).norm(), 1e-12 * rigid_condensed.norm());
  EXPECT_EQ(count_zero_modes(kept.K, 1e-10), 6);
  const Eigen::VectorXd m =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(kept.M.bottomRightCorner(3, 3)).eigenvalues();
  EXPECT_GT(m.minCoeff(), 0.0);
}

TEST(ShellCentre, NeedsTheConsistentMass) {
  EXPECT_THROW(shell_quad8_with_centre(distorted_element(), props(0.05, MassKind::Lumped)), std::invalid_argument);
}

// A plate of 8-node shells with consistent mass gets one centre node per
// element, at the element's centre (plate_mesh calls add_shell_centres as
// the model readers do); lumped and 4-node elements get none. The
// rigid-body modes leave the centres at zero, so the mass properties are
// the plate's (rho t A, centre of the plate) exactly.
TEST(ShellCentre, ModelsGetACentreNodePerConsistentQuad8) {
  const double a = 2.0, b = 1.0, t = 0.02;
  PlateMesh plate = plate_mesh(a, b, 4, 2, true, kE, kNu, kRho, t);
  Model& m = plate.model;
  const std::vector<NodeId> centres = coordinate_nodes(m);
  ASSERT_EQ(centres.size(), m.shells.size());
  EXPECT_EQ(m.nodes.size(), 37u + m.shells.size());  // the 8-node grid's 37 nodes, then the centres
  std::set<NodeId> distinct(centres.begin(), centres.end());
  EXPECT_EQ(distinct.size(), centres.size());
  for (const ShellElement& s : m.shells) {
    Vec3 mean = Vec3::Zero();
    for (int i = 0; i < 4; ++i) mean += 0.25 * m.position(s.nodes[static_cast<size_t>(i)]);
    EXPECT_LT((m.position(s.centre) - mean).norm(), 1e-14) << s.id;  // rectangles: the corners' mean
  }
  const size_t nodes = m.nodes.size();
  add_shell_centres(m);  // elements that have a centre keep it
  EXPECT_EQ(m.nodes.size(), nodes);
  m.validate();
  const MassProperties p = mass_properties(m);
  EXPECT_NEAR(p.mass, kRho * t * a * b, 1e-12 * kRho * t * a * b);
  EXPECT_LT((p.cog - Vec3(a / 2, b / 2, 0.0)).norm(), 1e-12);

  EXPECT_TRUE(coordinate_nodes(plate_mesh(a, b, 4, 2, true, kE, kNu, kRho, t, MassKind::Lumped).model).empty());
  EXPECT_TRUE(coordinate_nodes(plate_mesh(a, b, 4, 2, false, kE, kNu, kRho, t).model).empty());
}

TEST(ShellCentre, ValidationRefusesACentreThatIsNotOne) {
  PlateMesh plate = plate_mesh(2.0, 1.0, 2, 1, true, kE, kNu, kRho, 0.02);
  const Model& m = plate.model;
  ASSERT_NE(m.shells[0].centre, 0);
  Model shared = m;
  shared.shells[1].centre = shared.shells[0].centre;
  EXPECT_THROW(shared.validate(), ModelError);
  Model own = m;
  own.shells[0].centre = own.shells[0].nodes[2];
  EXPECT_THROW(own.validate(), ModelError);
  Model lumped = m;
  lumped.shells[0].mass = MassKind::Lumped;
  EXPECT_THROW(lumped.validate(), ModelError);
  // Nothing else may attach to a centre: it carries amplitudes, not motions.
  Model supported = m;
  supported.supports.push_back({"s", m.shells[0].centre, {true, true, true, true, true, true}});
  EXPECT_THROW(supported.validate(), ModelError);
  Model massed = m;
  massed.point_masses.push_back({"p", m.shells[1].centre, 1.0, {}});
  EXPECT_THROW(massed.validate(), ModelError);
  m.validate();
}

}  // namespace
}  // namespace rigflex::fe
