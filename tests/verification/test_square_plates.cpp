// NAFEMS's square plates, read from model files as a user writes them (a
// shell patch with the benchmark's divisions and no `order`, so the
// meshers' default element is what is checked): the thin FV12 (free) and
// FV16 (cantilevered) at their prescribed meshes; the thick, simply
// supported plate of R0016's Test 21 (at the end) against its closed form.
//
// FV12 (NAFEMS R0015; data and targets as quoted in Altair's OS-V 0420 and
// CATIA's NAFEMS set): a 10 x 10 m plate, t = 0.05 m, E = 200 GPa,
// nu = 0.3, rho = 8000 kg/m^3; in-plane motion and drilling held at every
// node, free otherwise (three rigid modes: w, and the two tilts). Prescribed
// meshes: 8 x 8 for 4-node, 4 x 4 for 8-node elements. Targets for modes
// 4-9: 1.622, 2.360, 2.922, 4.233, 4.233, 7.416 Hz.
//
// The exact thin-plate frequencies are Leissa's (Vibration of Plates,
// NASA SP-160, 1969, the free square plate at nu = 0.3): lambda = omega a^2
// sqrt(rho t / D) = 13.468, 19.596, 24.270, 34.801 (twice), 61.093 (twice),
// i.e. 1.6216, 2.3595, 2.9223, 4.1903, 7.3560 Hz. The targets of modes 7-9
// lie 1.0 % and 0.8 % above them; the default element at 16 x 16 lies
// within 0.07 % below them (Mindlin's shear and rotary inertia, and the
// four digits of Leissa's table).
//
// Tolerances against the exact values. At the prescribed 4 x 4 mesh, modes
// 4-8 within 1 % (measured +0.05 .. +0.45 %); modes 9 and 10 - which put
// about two 2.5 m elements on each half-wave - within 3 % (measured
// +2.58 %, the element converging from above: a stated limit of the
// prescribed mesh, docs/fe-core.md). At 8 x 8 every mode within 0.3 %
// (measured -0.02 .. +0.16 %). Against the targets at 4 x 4, modes 4-8
// within 1 % (measured -0.59 .. +0.46 %); the ninth is held against the
// exact value only (its target +1.75 % off: the target 0.8 % above the
// plate, the element 2.58 %).
//
// FV16 (NAFEMS R0015; Altair's OS-V 0430): the same plate clamped along
// x = 0 (x, y, z and the rotation about y held there, as the benchmark
// states; the in-plane motion and drilling of the others free), prescribed
// mesh 4 x 4 8-node elements; targets 0.421, 1.029, 2.582, 3.306, 3.753,
// 6.555 Hz (Barton's thin-plate values to 3-4 digits; the converged
// Mindlin plate lies 0.5-1.0 % below them, tests/fe/test_shell_verification.cpp).
// Tolerance 1 %: measured -0.67 .. +0.19 %.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "support/test_support.hpp"

namespace rigflex {
namespace {

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 8000.0, kT = 0.05, kA = 10.0;

// `supports` is the model file's supports section.
std::string model_text(int n, const char* name, const char* supports, double thickness = kT) {
  char buf[1600];
  const int written =
      std::snprintf(buf, sizeof buf,
                    "name: %s\nmaterials:\n  steel: {E: %g, nu: %g, rho: %g}\nshell_sections:\n"
                    "  plate: {material: steel, thickness: %g}\nshell_patches:\n"
                    "  - {id: plate, corners: [[0, 0, 0], [%g, 0, 0], [%g, %g, 0], [0, %g, 0]], divisions: [%d, %d], "
                    "section: plate}\n"
                    "node_sets:\n  all: {box: [[-1, -1, -1], [11, 11, 1]]}\n  root: {line: [[0, 0, 0], [0, 10, 0]]}\n"
                    "  far_x: {line: [[10, 0, 0], [10, 10, 0]]}\n  near_y: {line: [[0, 0, 0], [10, 0, 0]]}\n"
                    "  far_y: {line: [[0, 10, 0], [10, 10, 0]]}\n"
                    "supports:\n%s",
                    name, kE, kNu, kRho, thickness, kA, kA, kA, kA, n, n, supports);
  EXPECT_LT(written, static_cast<int>(sizeof buf)) << "model text truncated";
  return buf;
}

// Modes 4-10 (after the three rigid ones), Hz.
std::array<double, 7> elastic_frequencies(int n) {
  const Eigen::VectorXd f = test::elastic_modes(
      test::model_frequencies(model_text(n, "FV12", "  - {set: all, dofs: [UX, UY, RZ]}\n"), "FV12", 10), 3, 1.0);
  std::array<double, 7> out{};
  for (Eigen::Index k = 0; k < f.size(); ++k) out[static_cast<size_t>(k)] = f(k);
  return out;
}

// Leissa's thin-plate values for modes 4-10, Hz.
std::array<double, 7> thin_plate_solution() {
  const double D = kE * kT * kT * kT / (12.0 * (1.0 - kNu * kNu));
  const double scale = std::sqrt(D / (kRho * kT)) / (2.0 * M_PI * kA * kA);
  const std::array<double, 7> lambda{13.468, 19.596, 24.270, 34.801, 34.801, 61.093, 61.093};
  std::array<double, 7> f{};
  for (size_t k = 0; k < 7; ++k) f[k] = lambda[k] * scale;
  return f;
}

// f against `reference` mode by mode (the first being mode `first`), each
// within its tolerance.
void check(const char* name, std::span<const double> f, std::span<const double> reference,
           std::span<const double> tolerance, int first, const char* what, const char* against) {
  ASSERT_EQ(f.size(), reference.size());
  ASSERT_EQ(f.size(), tolerance.size());
  for (size_t k = 0; k < f.size(); ++k) {
    const double error = f[k] / reference[k] - 1.0;
    std::printf("  %s %s mode %zu: %.4f Hz, %s %.4f Hz, %+.2f %%\n", name, what, k + first, f[k], against, reference[k],
                100.0 * error);
    EXPECT_LT(std::abs(error), tolerance[k]) << name << " " << what << " mode " << k + first;
  }
}

TEST(FreePlate, TheDefaultShellAtFv12sMeshAgainstTheThinPlateSolution) {
  const std::array<double, 7> tolerance{0.01, 0.01, 0.01, 0.01, 0.01, 0.03, 0.03};
  check("FV12", elastic_frequencies(4), thin_plate_solution(), tolerance, 4, "default 4x4", "plate");
}

TEST(FreePlate, TheDefaultShellAtTwiceFv12sMesh) {
  std::array<double, 7> tolerance{};
  tolerance.fill(0.003);
  check("FV12", elastic_frequencies(8), thin_plate_solution(), tolerance, 4, "default 8x8", "plate");
}

TEST(FreePlate, TheDefaultShellMeetsFv12sTargetsForModes4To8) {
  const std::array<double, 5> target{1.622, 2.360, 2.922, 4.233, 4.233};
  const std::array<double, 5> tolerance{0.01, 0.01, 0.01, 0.01, 0.01};
  const std::array<double, 7> f = elastic_frequencies(4);
  check("FV12", std::span(f).first<5>(), target, tolerance, 4, "default 4x4", "target");
}

TEST(CantileveredPlate, TheDefaultShellMeetsFv16sTargetsAtItsMesh) {
  const Eigen::VectorXd f =
      test::model_frequencies(model_text(4, "FV16", "  - {set: root, dofs: [UX, UY, UZ, RY]}\n"), "FV16", 6);
  ASSERT_EQ(f.size(), 6);
  const std::array<double, 6> target{0.421, 1.029, 2.582, 3.306, 3.753, 6.555};
  const std::array<double, 6> tolerance{0.01, 0.01, 0.01, 0.01, 0.01, 0.01};
  check("FV16", std::span<const double>(f.data(), static_cast<size_t>(f.size())), target, tolerance, 1, "default 4x4",
        "target");
}

// ---------------------------------------------------------------- Test 21
// NAFEMS R0016 Test 21 (R0015's thick plate as shells; Abaqus's Benchmarks
// Test 21, Altair's OS-V 0470): the square plate 1 m thick, simply
// supported - in-plane motion and drilling held everywhere, w on the four
// edges, and the rotation along each edge (RX on x = 0, 10; RY on y = 0,
// 10). Targets 45.897, 109.44 (twice), 167.89, 204.51 (twice), 256.50
// (twice) Hz: the Mindlin plate's closed form with Mindlin's shear
// coefficient pi^2/12 (reproduced below to their digits). rigflex's shells
// take 5/6, which puts the plate 0.03-0.16 % higher.
//
// The closed form (Navier): mode (m, n) is w = W sin(alpha x) sin(beta y),
// the rotations X cos sin, Y sin cos, alpha = m pi / a, beta = n pi / a; the
// plate's energies then reduce to a 3 x 3 eigenproblem per (m, n).
double navier_frequency(int m, int n, double thickness, double shear_coefficient) {
  const double D = kE * std::pow(thickness, 3) / (12.0 * (1.0 - kNu * kNu)), G = kE / (2.0 * (1.0 + kNu));
  const double alpha = m * M_PI / kA, beta = n * M_PI / kA;
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();  // [W, X, Y]
  auto add = [&K](double stiffness, const Eigen::Vector3d& strain) { K += stiffness * strain * strain.transpose(); };
  add(D, Eigen::Vector3d(0, alpha, 0));  // curvature x
  add(D, Eigen::Vector3d(0, 0, beta));   // curvature y
  K(1, 2) += kNu * D * alpha * beta;     // Poisson coupling of the two curvatures
  K(2, 1) += kNu * D * alpha * beta;
  add(D * (1.0 - kNu) / 2.0, Eigen::Vector3d(0, beta, alpha));           // twist
  add(shear_coefficient * G * thickness, Eigen::Vector3d(alpha, 1, 0));  // shear xz
  add(shear_coefficient * G * thickness, Eigen::Vector3d(beta, 0, 1));   // shear yz
  const Eigen::Vector3d mass(kRho * thickness, kRho * std::pow(thickness, 3) / 12.0,
                             kRho * std::pow(thickness, 3) / 12.0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> eig(K, Eigen::Matrix3d(mass.asDiagonal()),
                                                                      Eigen::EigenvaluesOnly);
  return std::sqrt(eig.eigenvalues()(0)) / (2.0 * M_PI);
}

// The eight lowest, in order: (1,1), (1,2) (2,1), (2,2), (1,3) (3,1), (2,3) (3,2).
std::array<double, 8> thick_plate_solution(double shear_coefficient) {
  const std::array<std::array<int, 2>, 8> mn{{{1, 1}, {1, 2}, {2, 1}, {2, 2}, {1, 3}, {3, 1}, {2, 3}, {3, 2}}};
  std::array<double, 8> f{};
  for (size_t k = 0; k < 8; ++k) f[k] = navier_frequency(mn[k][0], mn[k][1], 1.0, shear_coefficient);
  return f;
}

constexpr std::array<double, 8> kTest21Targets{45.897, 109.44, 109.44, 167.89, 204.51, 204.51, 256.50, 256.50};

std::array<double, 8> test21_frequencies(int n) {
  const char* supports =
      "  - {set: all, dofs: [UX, UY, RZ]}\n  - {set: root, dofs: [UZ, RX]}\n  - {set: far_x, dofs: [UZ, RX]}\n"
      "  - {set: near_y, dofs: [UZ, RY]}\n  - {set: far_y, dofs: [UZ, RY]}\n";
  const Eigen::VectorXd f = test::model_frequencies(model_text(n, "Test21", supports, 1.0), "Test 21", 8);
  std::array<double, 8> out{};
  for (Eigen::Index k = 0; k < f.size() && k < 8; ++k) out[static_cast<size_t>(k)] = f(k);
  return out;
}

// The closed form with pi^2/12 is the targets to their printed digits
// (+-0.02 % at 45.897; measured within 0.005 %): it is what NAFEMS
// tabulates, and the derivation above is right.
TEST(ThickPlate, TheClosedFormWithMindlinsCoefficientIsTheTargets) {
  std::array<double, 8> tolerance{};
  tolerance.fill(2e-4);
  check("Test 21", thick_plate_solution(M_PI * M_PI / 12.0), kTest21Targets, tolerance, 1, "closed form pi^2/12",
        "target");
}

// The default 8-node shell against the closed form with its own 5/6. The
// element keeps its centre's three coordinates (the 9-node bending field's
// centre, with its inertia), so it converges as h^4 on this thick plate too
// (measured, modes 5-6: +0.28 % at 8 x 8, +0.018 % at 16 x 16). With the
// centre condensed statically instead, mode 7 read +0.99 % and +0.22 %: the
// centre's own dynamics left out, an error of order (omega h / c_shear)^2.
// Tolerances: 8 x 8 0.4 % (measured +0.004 .. +0.28 %), 16 x 16 0.03 %
// (+0.0002 .. +0.018 %); both fail on a shear coefficient of 1 instead of
// 5/6 (+2.0 % on mode 7), on the rotations' inertia left out (+2.9 %) and
// on the statically condensed centre.
TEST(ThickPlate, TheDefaultShellConvergesToTheMindlinPlate) {
  const std::array<double, 8> exact = thick_plate_solution(5.0 / 6.0);
  std::array<double, 8> coarse{}, fine{};
  coarse.fill(0.004);
  fine.fill(3e-4);
  check("Test 21", test21_frequencies(8), exact, coarse, 1, "default 8x8", "plate");
  check("Test 21", test21_frequencies(16), exact, fine, 1, "default 16x16", "plate");
}

// Against the published targets at 8 x 8 within 1 % (measured +0.03 ..
// +0.41 %: the element's error above plus the targets' coefficient, 0.03 -
// 0.16 % below the plate with 5/6).
TEST(ThickPlate, TheDefaultShellMeetsTheTargetsAt8x8) {
  std::array<double, 8> tolerance{};
  tolerance.fill(0.01);
  check("Test 21", test21_frequencies(8), kTest21Targets, tolerance, 1, "default 8x8", "target");
}

}  // namespace
}  // namespace rigflex
