// Zero-frequency modes: a free beam's six rigid-body motions, none in a
// clamped one, and a pinned one's three rotations named by node and DOF.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "reduction/modal_analysis.hpp"
#include "reduction/zero_frequency_modes.hpp"

namespace rigflex {
namespace {

// A steel box beam of 2 m along x in 4 elements; `held`: the DOFs of node 1 supported.
fe::Model beam(fe::DofMask held, bool support) {
  fe::Model m;
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850};
  fe::BeamSection s;
  s.name = "box";
  s.material = "steel";
  s.shape = fe::SectionShape::Box;
  s.width = s.height = 0.2;
  s.wall = 0.01;
  m.beam_sections["box"] = s;
  for (int i = 0; i <= 4; ++i) m.add_node(i + 1, {0.5 * i, 0, 0});
  for (int i = 0; i < 4; ++i) {
    fe::BeamElement b;
    b.id = "b" + std::to_string(i + 1);
    b.nodes = {i + 1, i + 2};
    b.section = "box";
    b.orientation = fe::Vec3(0, 0, 1);
    m.beams.push_back(b);
  }
  if (support) m.supports.push_back({"s1", 1, held});
  return m;
}

reduction::ModalAnalysis solve(const fe::Model& m, int count) {
  linalg::EigenOptions o;
  o.count = count;
  return reduction::run_modal_analysis(m, o);
}

TEST(ZeroFrequencyModes, AFreeBeamHasItsSixRigidBodyMotions) {
  const fe::Model m = beam({}, false);
  const auto a = solve(m, 8);
  ASSERT_TRUE(a.result.converged) << a.result.message;
  EXPECT_FALSE(reduction::is_supported(m));
  const auto z = reduction::zero_frequency_modes(m, a);
  ASSERT_EQ(z.size(), 6u);
  for (size_t k = 0; k < z.size(); ++k) EXPECT_EQ(z[k].mode, static_cast<Eigen::Index>(k));
  // The first flexible mode (a free-free box beam of 2 m: about 250 Hz) is not zero.
  EXPECT_GT(a.summary.frequencies_hz(6), 100.0);
}

TEST(ZeroFrequencyModes, AClampedBeamHasNone) {
  const fe::Model m = beam({true, true, true, true, true, true}, true);
  const auto a = solve(m, 4);
  ASSERT_TRUE(a.result.converged) << a.result.message;
  EXPECT_TRUE(reduction::is_supported(m));
  EXPECT_TRUE(reduction::zero_frequency_modes(m, a).empty());
}

TEST(ZeroFrequencyModes, APinnedBeamIsAMechanismOfThreeRotations) {
  const fe::Model m = beam({true, true, true, false, false, false}, true);
  const auto a = solve(m, 5);
  ASSERT_TRUE(a.result.converged) << a.result.message;
  const auto z = reduction::zero_frequency_modes(m, a);
  ASSERT_EQ(z.size(), 3u);
  // One of them is the spin about the beam's axis: every node's RX, nothing else.
  const auto spin = std::find_if(z.begin(), z.end(), [](const auto& x) {
    return std::all_of(x.largest.begin(), x.largest.end(), [](const std::string& d) { return d.ends_with(" RX"); });
  });
  ASSERT_NE(spin, z.end());
  EXPECT_EQ(spin->moving, 5);  // the five nodes' RX
  EXPECT_EQ(spin->largest.size(), 5u);
  EXPECT_EQ(spin->nodes.size(), 5u);  // each node once
}

}  // namespace
}  // namespace rigflex
