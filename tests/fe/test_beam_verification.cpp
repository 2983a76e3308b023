// Beam, point-mass and spring models against the shared verification cases.
// Targets are read from shared/verification; each tolerance is stated where
// it is used.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe/meshers.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/frame_models.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

using fe::Vec3;

// Euler-Bernoulli closed forms leave out the rotary inertia of the sections;
// Timoshenko references include it.
fe::Model bar_model(double length, int elements, const fe::BeamSection& section, const fe::Material& mat,
                    fe::BeamTheory theory) {
  fe::Model m;
  m.materials[mat.name] = mat;
  m.beam_sections[section.name] = section;
  fe::NodeMerger merger(m);
  fe::MemberSpec s;
  s.id = "bar";
  s.from = Vec3::Zero();
  s.to = Vec3(length, 0, 0);
  s.elements = elements;
  s.section = section.name;
  s.theory = theory;
  s.rotary_inertia = theory == fe::BeamTheory::Timoshenko;
  fe::mesh_member(m, merger, s);
  return m;
}

fe::Material steel(double E = 200e9, double nu = 0.3, double rho = 8000.0) { return {"steel", E, nu, rho}; }

fe::BeamSection rectangle(double width_y, double height_z) { return test::rect_section("rect", width_y, height_z); }

using test::fix;
using test::fix_all_nodes;
fe::NodeId node_at_x(const fe::Model& m, double x) {
  for (const auto& n : m.nodes)
    if (std::abs(n.x.x() - x) < 1e-9 && n.x.tail<2>().norm() < 1e-9) return n.id;
  throw std::runtime_error("no node");
}

enum : int { UX, UY, UZ, RX, RY, RZ };

Eigen::VectorXd modes_hz(const fe::Model& m, int count) {
  return test::checked_modal_analysis(m, count).summary.frequencies_hz;
}

void expect_modes(const Eigen::VectorXd& f, const std::vector<test::Target>& targets, int first_mode_offset,
                  double rel_tol, const std::string& what) {
  for (const auto& t : targets) {
    const double got = f(t.mode - 1 + first_mode_offset);
    EXPECT_NEAR(got / t.freq_hz, 1.0, rel_tol) << what << " mode " << t.mode << ": " << got << " Hz vs " << t.freq_hz;
  }
}

// CF-BEAM-EB: 20 Hermite elements converge the first four bending modes to
// about 1e-5 (h^4 error); targets are printed to 5-6 digits. 2e-4 covers both.
constexpr double kEulerTol = 2e-4;

fe::Model planar_bar(int elements, fe::BeamTheory theory = fe::BeamTheory::EulerBernoulli) {
  fe::Model m = bar_model(5.0, elements, rectangle(0.125, 0.125), steel(), theory);
  fix_all_nodes(m, {UZ, RX, RY});  // bending in the x-y plane only
  return m;
}

TEST(BeamVerification, EulerBernoulliCantilever) {
  fe::Model m = planar_bar(20);
  fix(m, node_at_x(m, 0), {UX, UY, RZ});
  expect_modes(modes_hz(m, 4), test::verification_targets("beam_euler_bernoulli_closed_form.yaml"), 0, kEulerTol,
               "clamped-free");
}

TEST(BeamVerification, EulerBernoulliPinnedPinned) {
  fe::Model m = planar_bar(20);
  fix(m, node_at_x(m, 0), {UX, UY});
  fix(m, node_at_x(m, 5), {UY});
  expect_modes(modes_hz(m, 4), test::verification_targets("beam_euler_bernoulli_closed_form.yaml", "pinned-pinned"),
               0, kEulerTol, "pinned-pinned");
}

TEST(BeamVerification, EulerBernoulliClampedClamped) {
  fe::Model m = planar_bar(20);
  fix(m, node_at_x(m, 0), {UX, UY, RZ});
  fix(m, node_at_x(m, 5), {UX, UY, RZ});
  expect_modes(modes_hz(m, 4),
               test::verification_targets("beam_euler_bernoulli_closed_form.yaml", "clamped-clamped"), 0, kEulerTol,
               "clamped-clamped");
}

TEST(BeamVerification, EulerBernoulliClampedPinned) {
  fe::Model m = planar_bar(20);
  fix(m, node_at_x(m, 0), {UX, UY, RZ});
  fix(m, node_at_x(m, 5), {UY});
  expect_modes(modes_hz(m, 4), test::verification_targets("beam_euler_bernoulli_closed_form.yaml", "clamped-pinned"),
               0, kEulerTol, "clamped-pinned");
}

TEST(BeamVerification, EulerBernoulliFreeFreeHasRigidModesFirst) {
  fe::Model m = planar_bar(20);
  const Eigen::VectorXd f = modes_hz(m, 7);
  // In-plane rigid-body modes: UX, UY, RZ -> three zeros; 1e-6 Hz is far
  // below the first elastic mode (25.7 Hz) and far above round-off.
  for (int k = 0; k < 3; ++k) EXPECT_LT(f(k), 1e-3) << "rigid mode " << k;
  expect_modes(f, test::verification_targets("beam_euler_bernoulli_closed_form.yaml", "free-free"), 3, kEulerTol,
               "free-free");
}

TEST(BeamVerification, AxialFixedFree) {
  // Linear axial interpolation with consistent mass errs by (k h)^2/24: with
  // 100 elements, 1e-4 for the second mode.
  fe::Model m = bar_model(5.0, 100, rectangle(0.125, 0.125), steel(), fe::BeamTheory::EulerBernoulli);
  fix_all_nodes(m, {UY, UZ, RX, RY, RZ});
  fix(m, node_at_x(m, 0), {UX});
  expect_modes(modes_hz(m, 2), test::verification_targets("beam_euler_bernoulli_closed_form.yaml", "axial fixed-free"),
               0, 2e-4, "axial");
}

TEST(BeamVerification, TimoshenkoShortBeamSdll01) {
  // The VPCS values come from Timoshenko's book formulation and differ from
  // the Timoshenko closed form by up to 0.14% (file note): 0.2% tolerance.
  fe::Model m = bar_model(1.0, 40, rectangle(0.2, 0.1), {"steel", 2e11, 0.3, 7800}, fe::BeamTheory::Timoshenko);
  fix_all_nodes(m, {UZ, RX, RY});
  fix(m, node_at_x(m, 0), {UX, UY});
  fix(m, node_at_x(m, 1), {UY});
  expect_modes(modes_hz(m, 6), test::verification_targets("beam_timoshenko_short_ss_beam_sdll01.yaml"), 0, 2e-3,
               "SDLL01");
}

TEST(BeamVerification, TimoshenkoClosedFormSdll01) {
  // Against the Timoshenko pinned-pinned closed form with the same shear
  // coefficient: discretization error only. The consistent Timoshenko mass
  // converges as h^2 (measured: 9.5e-4 at 40 elements, 6e-5 at 160 for the
  // third flexural mode), so 160 elements and 2e-4.
  fe::Model m = bar_model(1.0, 160, rectangle(0.2, 0.1), {"steel", 2e11, 0.3, 7800}, fe::BeamTheory::Timoshenko);
  fix_all_nodes(m, {UZ, RX, RY});
  fix(m, node_at_x(m, 0), {UX, UY});
  fix(m, node_at_x(m, 1), {UY});
  const Eigen::VectorXd f = modes_hz(m, 4);
  const YAML::Node cf = test::verification_case("beam_timoshenko_short_ss_beam_sdll01.yaml")["closed_form_check"]["computed_hz"];
  EXPECT_NEAR(f(0) / cf["flexure_1"].as<double>(), 1.0, 2e-4);
  EXPECT_NEAR(f(2) / cf["flexure_2"].as<double>(), 1.0, 2e-4);
  EXPECT_NEAR(f(3) / cf["flexure_3"].as<double>(), 1.0, 2e-4);
}

TEST(BeamVerification, NafemsFv5DeepBeam) {
  // 40 Timoshenko elements: torsion and extension (linear interpolation)
  // err by (k h)^2/24 <= 6e-4 for the 2nd torsion mode; targets are printed
  // to 4-5 digits. 2e-3.
  fe::Model m = bar_model(10.0, 40, rectangle(2.0, 2.0), steel(), fe::BeamTheory::Timoshenko);
  fix(m, node_at_x(m, 0), {UX, UY, UZ, RX});
  fix(m, node_at_x(m, 10), {UY, UZ});
  expect_modes(modes_hz(m, 9), test::verification_targets("nafems_fv5_deep_simply_supported_beam.yaml"), 0, 2e-3,
               "FV5");
}

// FV2's targets are the closed forms of inextensible arms (file note).
// `axial_scale` multiplies EA while keeping rho A, to reach that limit.
fe::Model double_cross(double axial_scale) {
  fe::Model m;
  m.materials["steel"] = {"steel", 200e9, 0.3, 8000.0 / axial_scale};
  fe::BeamSection sq;
  sq.name = "arm";
  sq.material = "steel";
  sq.A = 0.125 * 0.125 * axial_scale;
  sq.Iy = sq.Iz = std::pow(0.125, 4) / 12;
  sq.J = 0.1406 * std::pow(0.125, 4);
  m.beam_sections[sq.name] = sq;
  fe::NodeMerger merger(m);
  const YAML::Node tips = test::verification_case("nafems_fv2_pin_ended_double_cross.yaml")["geometry"]["arm_tip_coordinates_m"];
  for (size_t i = 0; i < tips.size(); ++i) {
    fe::MemberSpec s;
    s.id = "arm" + std::to_string(i);
    s.from = Vec3::Zero();
    s.to = Vec3(tips[i][0].as<double>(), tips[i][1].as<double>(), 0);
    s.elements = 8;
    s.section = "arm";
    s.theory = fe::BeamTheory::EulerBernoulli;
    s.rotary_inertia = false;
    const auto ids = fe::mesh_member(m, merger, s);
    fix(m, ids.back(), {UX, UY});
  }
  fix_all_nodes(m, {UZ, RX, RY});
  return m;
}

TEST(BeamVerification, NafemsFv2DoubleCrossInextensibleLimit) {
  // 8 Euler-Bernoulli elements per arm, EA x 1e4: targets printed to 5
  // digits (1e-4) plus a discretization error near 1e-4 for mode 16: 5e-4.
  expect_modes(modes_hz(double_cross(1e4), 16), test::verification_targets("nafems_fv2_pin_ended_double_cross.yaml"),
               0, 5e-4, "FV2 inextensible");
}

TEST(BeamVerification, NafemsFv2DoubleCrossAsSpecified) {
  // With the real EA the centre can translate, which lowers the repeated
  // families a few tenths of a percent below the inextensible closed forms
  // (measured 0.16% and 0.51%). The precision claim is the test above; this
  // one checks the model as NAFEMS specifies it against a 1% engineering
  // acceptance, which a 2% error in EI would already break.
  expect_modes(modes_hz(double_cross(1.0), 16), test::verification_targets("nafems_fv2_pin_ended_double_cross.yaml"),
               0, 1e-2, "FV2");
}

fe::Model portal(double beam_I) { return test::portal_frame(beam_I); }

TEST(BeamVerification, PortalFrameSwayIsExact) {
  // Massless Hermite members with masses at the joints: exact to round-off
  // up to the axial compliance of A = 1e3 m^2 (relative effect ~1e-7).
  // M is singular here (massless rotations), which the solver must handle.
  const Eigen::VectorXd f = modes_hz(portal(2e-4), 1);
  const double target = test::verification_frequencies("portal_frame_sway_closed_form.yaml")[0];
  EXPECT_NEAR(f(0) / target, 1.0, 1e-6);
}

TEST(BeamVerification, PortalFrameRigidBeamLimit) {
  const Eigen::VectorXd f = modes_hz(portal(1e6), 1);
  const double target = test::verification_frequencies("portal_frame_sway_closed_form.yaml", "rigid beam (Ib -> infinity), same columns and masses")[0];
  EXPECT_NEAR(f(0) / target, 1.0, 1e-6);
}

}  // namespace
}  // namespace rigflex
