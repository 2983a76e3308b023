// Rigid couplings (exact elimination) and mass properties against closed forms.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "fe/assembly.hpp"
#include "fe/element_loop.hpp"
#include "fe/error.hpp"
#include "fe/mass_properties.hpp"
#include "fe/meshers.hpp"
#include "support/frame_models.hpp"

namespace rigflex {
namespace {

using fe::Vec3;

Eigen::Matrix3d skew(const Vec3& r) {
  Eigen::Matrix3d S;
  S << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return S;
}

TEST(RigidCoupling, SpiderMovesRigidlyUnderLoad) {
  // A reference node drives four legs' top nodes; the legs stand on the floor.
  fe::Model m = test::steel_model();
  m.beam_sections["tube"] = test::tube_section("tube", 0.1, 0.005);
  fe::NodeMerger merger(m);
  std::vector<fe::NodeId> tops;
  for (const Vec3& p : {Vec3(1, 0, 0), Vec3(0, 1.5, 0.2), Vec3(-1, 0, 0.1), Vec3(0, -1, -0.1)}) {
    const std::string id = "leg" + std::to_string(tops.size());
    const auto ids = test::member(m, merger, id, p - Vec3(0, 0, 2), p, 3, "tube");
    test::clamp(m, "base" + id, ids.front());
    tops.push_back(ids.back());
  }
  const fe::NodeId ref = merger.at(Vec3(0.1, 0.2, 0.5));
  m.couplings.push_back({"spider", ref, tops, {true, true, true, true, true, true}});
  const fe::AssembledSystem sys = fe::assemble(m);

  Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.dofs.free_count());
  const std::array<double, 6> load{1e4, -2e4, 3e4, 5e3, -4e3, 7e3};
  for (Eigen::Index j = 0; j < f.size(); ++j)
    if (sys.dofs.node[static_cast<size_t>(j)] == ref) f(j) = load[static_cast<size_t>(sys.dofs.local[static_cast<size_t>(j)])];
  Eigen::SimplicialLDLT<fe::SpMat> solver(sys.K);
  ASSERT_EQ(solver.info(), Eigen::Success);
  const Eigen::VectorXd u = sys.dofs.expand(solver.solve(f));

  const auto ir = static_cast<Eigen::Index>(6 * m.node_index(ref));
  const Vec3 ur = u.segment<3>(ir), tr = u.segment<3>(ir + 3);
  ASSERT_GT(ur.norm(), 0.0);
  for (fe::NodeId d : tops) {
    const auto id = static_cast<Eigen::Index>(6 * m.node_index(d));
    const Vec3 expected = ur + tr.cross(m.position(d) - m.position(ref));
    // The elimination is exact: differences are round-off of the solve.
    EXPECT_LT((u.segment<3>(id) - expected).norm(), 1e-12 * ur.norm());
    EXPECT_LT((u.segment<3>(id + 3) - tr).norm(), 1e-12 * tr.norm());
  }
}

TEST(RigidCoupling, PointMassOnRigidOffsetHasParallelAxisInertia) {
  fe::Model m;
  m.add_node(1, {0.5, 0.5, 1.0});
  const Vec3 r(0.3, -0.2, 0.5);
  m.add_node(2, Vec3(0.5, 0.5, 1.0) + r);
  const double mass = 7.0;
  const std::array<double, 6> J0{2.0, 3.0, 4.0, 0.1, -0.2, 0.3};
  m.point_masses.push_back({"pm", 2, mass, J0});
  m.couplings.push_back({"offset", 1, {2}, {true, true, true, true, true, true}});
  const fe::AssembledSystem sys = fe::assemble(m);
  ASSERT_EQ(sys.dofs.free_count(), 6);  // only the reference node remains
  const Eigen::MatrixXd M = Eigen::MatrixXd(sys.M);

  Eigen::Matrix3d Jown;
  Jown << J0[0], J0[3], J0[4], J0[3], J0[1], J0[5], J0[4], J0[5], J0[2];
  Eigen::Matrix<double, 6, 6> expected;
  expected.topLeftCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  expected.topRightCorner<3, 3>() = -mass * skew(r);
  expected.bottomLeftCorner<3, 3>() = mass * skew(r);
  expected.bottomRightCorner<3, 3>() = Jown + mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  EXPECT_LT((M - expected).norm(), 1e-13 * expected.norm());
}

TEST(MassProperties, SlenderBeamMatchesClosedForm) {
  fe::Model m = test::steel_model();
  const fe::BeamSection s = test::tube_section("tube", 0.1, 0.005);
  m.beam_sections["tube"] = s;
  fe::NodeMerger merger(m);
  test::member(m, merger, "b", Vec3(1, 2, 3), Vec3(3, 2, 3), 5, "tube");
  const fe::MassProperties p = fe::mass_properties(m);
  const fe::SectionProperties sp = fe::section_properties(s, 0.3);
  const double L = 2.0, rho = 7850, mass = rho * sp.A * L;
  // Rigid motions are in the span of the element interpolation, so the
  // consistent mass reproduces them exactly: round-off tolerances.
  EXPECT_NEAR(p.mass / mass, 1.0, 1e-12);
  EXPECT_LT((p.cog - Vec3(2, 2, 3)).norm(), 1e-12);
  EXPECT_NEAR(p.inertia(0, 0) / (rho * sp.Ip() * L), 1.0, 1e-10);
  EXPECT_NEAR(p.inertia(1, 1) / (mass * L * L / 12 + rho * sp.Iy * L), 1.0, 1e-10);
  EXPECT_NEAR(p.inertia(2, 2) / (mass * L * L / 12 + rho * sp.Iz * L), 1.0, 1e-10);
  EXPECT_LT(std::abs(p.inertia(0, 1)) + std::abs(p.inertia(0, 2)) + std::abs(p.inertia(1, 2)), 1e-10 * p.inertia(1, 1));
}

TEST(MassProperties, ProductsOfInertiaUseTheNegativeIntegralConvention) {
  fe::Model m;
  m.add_node(1, {1, 1, 0});
  m.add_node(2, {-1, -1, 0});
  m.add_node(3, {0, 0, 2});
  m.point_masses.push_back({"a", 1, 1.0, {}});
  m.point_masses.push_back({"b", 2, 1.0, {}});
  m.point_masses.push_back({"c", 3, 2.0, {}});
  const fe::MassProperties p = fe::mass_properties(m);
  // CoG at (0,0,1); Jxy = -sum m x y = -(1 + 1) = -2 (shared/spec).
  EXPECT_NEAR(p.mass, 4.0, 1e-14);
  EXPECT_LT((p.cog - Vec3(0, 0, 1)).norm(), 1e-14);
  EXPECT_NEAR(p.inertia(0, 1), -2.0, 1e-13);
  EXPECT_NEAR(p.inertia(0, 0), 1 * (1 + 1) + 1 * (1 + 1) + 2 * 1, 1e-13);
  EXPECT_NEAR(p.inertia(2, 2), 4.0, 1e-13);
}

// A model built in code skips the reader's physical ranges: a modulus at
// the top of the double range overflows a short beam's bending stiffness
// (12 E I / L^3). Assembly refuses it, naming the beam, instead of
// spreading infinities into the solve.
TEST(ElementMatrices, ANonFiniteStiffnessIsRefusedNamingTheElement) {
  fe::Model m = test::steel_model();
  m.materials["steel"].E = 1.0e308;
  m.beam_sections["tube"] = test::tube_section("tube", 0.1, 0.005);
  fe::NodeMerger merger(m);
  const auto ids = test::member(m, merger, "post", Vec3(0, 0, 0), Vec3(0, 0, 0.01), 1, "tube");
  test::clamp(m, "base", ids.front());
  m.validate();
  try {
    fe::check_element_matrices(m);
    FAIL() << "no error";
  } catch (const fe::ModelError& e) {
    EXPECT_EQ(e.where().kind, "beam");
    EXPECT_EQ(e.where().id, m.beams.front().id);
    // The shear-flexibility ratio 12 E I / (k G A L^2) enters the
    // Timoshenko mass matrix too: both are named.
    EXPECT_NE(std::string(e.what()).find("stiffness and mass matrices are not finite"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)fe::assemble(m), fe::ModelError);
  // The same beam of steel passes.
  m.materials["steel"].E = 2.1e11;
  EXPECT_NO_THROW(fe::check_element_matrices(m));
}

}  // namespace
}  // namespace rigflex
