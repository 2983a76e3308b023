// Point masses and springs against the discrete verification cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reduction/modal_analysis.hpp"
#include "support/frame_models.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

using fe::Vec3;

using test::axial_spring;

TEST(DiscreteVerification, SpringMassChainSdld02OnAnObliqueAxis) {
  // Eight masses on the axis (3,4,0)/5 with oblique axial springs: the
  // transverse in-plane DOFs carry mass but no stiffness, so 8 zero modes
  // precede the chain's 8 (a hard case for the solver: an 8-fold zero).
  const YAML::Node c = test::verification_case("discrete_spring_mass_chain_sdld02.yaml");
  fe::Model m;
  for (int i = 1; i <= 8; ++i) {
    const YAML::Node p = c["geometry"]["nodes_m"]["P" + std::to_string(i)];
    m.add_node(i, {p[0].as<double>(), p[1].as<double>(), p[2].as<double>()});
    m.point_masses.push_back({"m" + std::to_string(i), i, 10.0, {}});
    m.supports.push_back({"z" + std::to_string(i), i, {false, false, true, false, false, false}});
  }
  const Vec3 axis = Vec3(3, 4, 0).normalized();
  for (int i = 1; i < 8; ++i) m.springs.push_back(axial_spring("k" + std::to_string(i), i, i + 1, 1e5));
  m.springs.push_back(axial_spring("g1", 1, std::nullopt, 1e5, axis));
  m.springs.push_back(axial_spring("g8", 8, std::nullopt, 1e5, axis));
  const auto a = test::checked_modal_analysis(m, 16);
  const auto targets = test::verification_targets("discrete_spring_mass_chain_sdld02.yaml");
  for (int k = 0; k < 8; ++k) EXPECT_LT(a.summary.frequencies_hz(k), 1e-4) << "zero mode " << k;
  for (const auto& t : targets) {
    const double got = a.summary.frequencies_hz(7 + t.mode);
    // Targets printed to 5 digits: 1e-4 (the file's stated precision).
    EXPECT_NEAR(got / t.freq_hz, 1.0, 1e-4) << "mode " << t.mode;
    // Closed form f_n = (1/pi) sqrt(k/m) sin(n pi / 18): round-off only.
    const double exact = std::sqrt(1e5 / 10.0) / std::numbers::pi * std::sin(t.mode * std::numbers::pi / 18.0);
    EXPECT_NEAR(got / exact, 1.0, 1e-10) << "mode " << t.mode;
  }
}

TEST(DiscreteVerification, TwoMassThreeSpringVm89) {
  fe::Model m;
  m.add_node(1, {0, 0, 0});
  m.add_node(2, {1, 0, 0});
  m.add_node(3, {2, 0, 0});
  m.add_node(4, {3, 0, 0});
  test::clamp(m, "g1", 1);
  test::clamp(m, "g4", 4);
  for (int n : {2, 3}) m.supports.push_back({"yz" + std::to_string(n), n, {false, true, true, false, false, false}});
  m.springs.push_back(axial_spring("k1", 1, 2, 200.0));
  m.springs.push_back(axial_spring("k2", 2, 3, 800.0));
  m.springs.push_back(axial_spring("k3", 3, 4, 200.0));
  m.point_masses.push_back({"m1", 2, 0.5, {}});
  m.point_masses.push_back({"m2", 3, 1.0, {}});
  const auto a = test::checked_modal_analysis(m, 2);
  for (const auto& t : test::verification_targets("discrete_two_mass_spring_vm89.yaml"))
    EXPECT_NEAR(a.summary.frequencies_hz(t.mode - 1) / t.freq_hz, 1.0, 1e-4) << "mode " << t.mode;
  // Amplitude ratio of mode 1 (ANSYS target 0.92116, 5 digits).
  const Eigen::VectorXd x = a.result.vectors.col(0);
  EXPECT_NEAR(x(0) / x(1), 0.92116, 1e-4);
}

TEST(DiscreteVerification, SixDofPointMassSdld400) {
  fe::Model m;
  m.add_node(1, {0, 0, 0});
  m.point_masses.push_back({"mass", 1, 10.0, {10.0, 10.0, 10.0, 0.0, 0.0, 0.0}});
  m.springs.push_back(test::grounded_spring("springs", 1, {160, 180, 1280, 180, 1280, 1960}));
  const auto a = test::checked_modal_analysis(m, 6);
  // Printed to 6 digits; repeated pairs must both be found.
  for (const auto& t : test::verification_targets("discrete_single_node_6dof_mass_sdld400.yaml"))
    EXPECT_NEAR(a.summary.frequencies_hz(t.mode - 1) / t.freq_hz, 1.0, 2e-6) << "mode " << t.mode;
}

}  // namespace
}  // namespace rigflex
