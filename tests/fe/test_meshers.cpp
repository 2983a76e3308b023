// Meshers: box girders against beam theory, and the rig frame builders.
#include <gtest/gtest.h>

#include "fe/meshers.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/frame_models.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

using fe::Vec3;

Eigen::VectorXd lowest_hz(const fe::Model& m, int count) {
  return test::checked_modal_analysis(m, count).summary.frequencies_hz;
}

fe::Model box_girder_cantilever(bool quadratic, int along, int across) {
  fe::Model m = test::steel_model();
  fe::NodeMerger merger(m);
  fe::BoxGirderSpec g;
  g.id = "g";
  g.from = Vec3::Zero();
  g.to = Vec3(4, 0, 0);
  g.width = 0.3;
  g.height = 0.4;
  g.web_thickness = 0.010;
  g.flange_thickness = 0.015;
  g.material = "steel";
  g.n_along = along;
  g.n_width = g.n_height = across;
  g.quadratic = quadratic;
  g.end_plates = false;
  const fe::BoxGirderNodes ends = fe::mesh_box_girder(m, merger, g);
  test::clamp(m, "root", *ends.start_reference);
  return m;
}

fe::Model box_beam_cantilever() {
  fe::Model m = test::steel_model();
  m.beam_sections["box"] = test::box_section("box", 0.3, 0.4, 0.010, 0.015);
  fe::NodeMerger merger(m);
  const auto ids = test::member(m, merger, "b", Vec3::Zero(), Vec3(4, 0, 0), 40, "box");
  test::clamp(m, "root", ids.front());
  return m;
}

// Beam theory and the shell girder differ by the mid-surface idealization of
// the walls (~(t/h)^2, 0.1%), shear lag and the rigid root section: a 3%
// band. A girder meshed with the wrong wall thickness (10% in I) fails it.
TEST(Meshers, BoxGirderOfShellsBendsLikeABoxBeam) {
  const Eigen::VectorXd beam = lowest_hz(box_beam_cantilever(), 2);
  for (bool quadratic : {false, true}) {
    const fe::Model shells = quadratic ? box_girder_cantilever(true, 16, 2) : box_girder_cantilever(false, 32, 4);
    const Eigen::VectorXd f = lowest_hz(shells, 2);
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(f(k) / beam(k), 1.0, 0.03) << (quadratic ? "8-node" : "MITC4") << " mode " << k + 1 << ": "
                                             << f(k) << " vs beam " << beam(k);
  }
}

TEST(Meshers, MemberStationsBecomeNodes) {
  fe::Model m;
  fe::NodeMerger merger(m);
  fe::MemberSpec s;
  s.id = "m";
  s.to = Vec3(1, 0, 0);
  s.elements = 4;
  s.section = "x";
  s.stations = {0.3, 0.5};  // 0.5 is already a division point
  const auto ids = fe::mesh_member(m, merger, s);
  ASSERT_EQ(ids.size(), 6u);
  EXPECT_NEAR(m.position(ids[2]).x(), 0.3, 1e-15);
  EXPECT_EQ(m.beams.size(), 5u);
}

TEST(Meshers, FixedFrameHangsEachJointFromTheNearestBeam) {
  fe::Model m = test::steel_model();
  m.beam_sections["col"] = test::box_section("col", 0.2, 0.2, 0.01);
  fe::FixedFrameSpec f;
  f.column_bases = {Vec3(-1.5, -1, 0), Vec3(1.5, -1, 0), Vec3(1.5, 1, 0), Vec3(-1.5, 1, 0)};
  f.height = 3;
  f.column_section = f.beam_section = "col";
  f.joints = {Vec3(1.0, -1.0, 2.8), Vec3(-1.0, -1.0, 2.8), Vec3(0.0, 1.0, 3.0)};
  fe::build_fixed_frame(m, f);
  const auto joints = m.node_set("upper_joints");
  ASSERT_EQ(joints.size(), 3u);
  EXPECT_LT((m.position(joints[0]) - f.joints[0]).norm(), 1e-12);
  // Joints 1 and 2 hang below the beam: couplings; joint 3 lies on it: a beam node.
  EXPECT_EQ(m.couplings.size(), 2u);
  EXPECT_EQ(m.couplings[0].reference, joints[0]);
  EXPECT_LT((m.position(m.couplings[0].dependents[0]) - Vec3(1.0, -1.0, 3.0)).norm(), 1e-12);
  EXPECT_EQ(m.supports.size(), 4u);
  const Eigen::VectorXd hz = lowest_hz(m, 3);
  EXPECT_GT(hz(0), 1.0);  // clamped at the floor: no rigid-body modes
}

TEST(Meshers, CarryingFrameFloatsWithSixRigidBodyModes) {
  fe::Model m = test::steel_model();
  m.beam_sections["tube"] = test::tube_section("tube", 0.1, 0.005);
  fe::CarryingFrameSpec c;
  c.corner_min = Vec3(-1, -0.8, 0);
  c.corner_max = Vec3(1, 0.8, 0);
  c.bays_x = 2;
  c.bays_y = 2;
  c.section = "tube";
  c.joints = {Vec3(0.8, -0.8, 0.2), Vec3(-0.8, -0.8, 0.2), Vec3(0, 0.8, 0.2)};
  fe::build_carrying_frame(m, c);
  EXPECT_EQ(m.node_set("lower_joints").size(), 3u);
  const Eigen::VectorXd hz = lowest_hz(m, 7);
  // Six rigid-body modes, then the first elastic mode (tens of Hz).
  for (int k = 0; k < 6; ++k) EXPECT_LT(hz(k), 1e-3 * hz(6)) << k;
  EXPECT_GT(hz(6), 1.0);
}

}  // namespace
}  // namespace rigflex
