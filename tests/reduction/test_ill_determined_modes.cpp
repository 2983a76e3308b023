// Ill-determined modes: a 1 kg block on soft springs carrying two 1 g parts
// on stiff springs. Its six mount modes sit near 0.16 Hz (translations)
// and 1.6 Hz (rotations); the parts' own modes at sqrt(k / 1 g) and above.
// With k = 1e10 N/m, K_ii / M_ii reaches 1e15 (the parts' rotations)
// against mount eigenvalues of 1-100 (rad/s)^2, and rounding leaves their
// residual ratios at 2e-6..3e-5 (measured): they are reported. With k = 1e4
// the same model (K_ii / M_ii 1e9) reads below 1e-9: nothing is.
#include <gtest/gtest.h>

#include <string>

#include "reduction/ill_determined_modes.hpp"
#include "reduction/modal_analysis.hpp"

namespace rigflex {
namespace {

fe::Model mounted_block(double bracket_stiffness) {
  fe::Model m;
  for (int i = 0; i < 3; ++i) m.add_node(i + 1, {0.1 * i, 0, 0});
  m.point_masses.push_back({"block", 1, 1.0, {1e-2, 1e-2, 1e-2, 0, 0, 0}});
  m.point_masses.push_back({"part2", 2, 1e-3, {1e-5, 1e-5, 1e-5, 0, 0, 0}});
  m.point_masses.push_back({"part3", 3, 1e-3, {1e-5, 1e-5, 1e-5, 0, 0, 0}});
  fe::Spring mount;
  mount.id = "mount";
  mount.node = 1;
  mount.stiffness = {1, 1, 1, 1, 1, 1};
  m.springs.push_back(mount);
  for (int i = 2; i <= 3; ++i) {
    fe::Spring s;
    s.id = "bracket" + std::to_string(i);
    s.node = i - 1;
    s.other = i;
    s.stiffness = {bracket_stiffness, bracket_stiffness, bracket_stiffness,
                   bracket_stiffness, bracket_stiffness, bracket_stiffness};
    m.springs.push_back(s);
  }
  return m;
}

reduction::ModalAnalysis solve(const fe::Model& m) {
  linalg::EigenOptions o;
  o.count = 8;
  return reduction::run_modal_analysis(m, o);
}

TEST(IllDeterminedModes, AStiffBracketOnASoftMountLeavesTheMountModesVague) {
  const reduction::ModalAnalysis a = solve(mounted_block(1e10));
  ASSERT_TRUE(a.result.converged) << a.result.message;
  // The translation modes of the mount: sqrt(1 / 1.002) / (2 pi).
  EXPECT_NEAR(a.summary.frequencies_hz(0), 0.1590, 1e-3);
  EXPECT_GT(reduction::stiffest_ratio(a.system), 1e14);
  const auto vague = reduction::ill_determined_modes(a, {});
  ASSERT_FALSE(vague.empty());
  EXPECT_EQ(vague.front().mode, 0);
  for (const auto& v : vague) {
    EXPECT_GT(v.relative_error, 1e-6);
    EXPECT_LT(v.relative_error, 1.0);
    EXPECT_LT(v.frequency_hz, 2.0);  // only the mount's modes
  }
  const std::string line = reduction::describe(vague, a);
  EXPECT_NE(line.find("mode"), std::string::npos);
  EXPECT_NE(line.find("rigid coupling"), std::string::npos);
  // Modes listed as of zero frequency are not judged.
  std::vector<reduction::ZeroFrequencyMode> zero;
  for (const auto& v : vague) {
    reduction::ZeroFrequencyMode z;
    z.mode = v.mode;
    zero.push_back(z);
  }
  EXPECT_TRUE(reduction::ill_determined_modes(a, zero).empty());
}

TEST(IllDeterminedModes, TheSameModelWithAModerateBracketHasNone) {
  const reduction::ModalAnalysis a = solve(mounted_block(1e4));
  ASSERT_TRUE(a.result.converged) << a.result.message;
  EXPECT_TRUE(reduction::ill_determined_modes(a, {}).empty());
  EXPECT_LT(reduction::stiffest_ratio(a.system), 1e10);
  EXPECT_LT(a.result.residuals.maxCoeff(), 1e-9);
  EXPECT_EQ(reduction::describe({}, a), "");
  // The same model judged against a limit below its rounding level: the
  // function reads the ratios, it does not ignore them.
  EXPECT_FALSE(reduction::ill_determined_modes(a, {}, 1e-15).empty());
}

}  // namespace
}  // namespace rigflex
