// NAFEMS's thin square plates at their prescribed meshes, read from model
// files as a user writes them (a shell patch with the benchmark's divisions
// and no `order`, so the meshers' default element is what is checked): FV12
// free, FV16 cantilevered.
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

#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"

namespace rigflex {
namespace {

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 8000.0, kT = 0.05, kA = 10.0;

// `supports` is the model file's supports section.
std::string model_text(int n, const char* name, const char* supports) {
  char buf[800];
  std::snprintf(buf, sizeof buf,
                "name: %s\nmaterials:\n  steel: {E: %g, nu: %g, rho: %g}\nshell_sections:\n"
                "  plate: {material: steel, thickness: %g}\nshell_patches:\n"
                "  - {id: plate, corners: [[0, 0, 0], [%g, 0, 0], [%g, %g, 0], [0, %g, 0]], divisions: [%d, %d], "
                "section: plate}\n"
                "node_sets:\n  all: {box: [[-1, -1, -1], [11, 11, 1]]}\n  root: {line: [[0, 0, 0], [0, 10, 0]]}\n"
                "supports:\n%s",
                name, kE, kNu, kRho, kT, kA, kA, kA, kA, n, n, supports);
  return buf;
}

// Modes 4-10 (after the three rigid ones), Hz.
std::array<double, 7> elastic_frequencies(int n) {
  const io::ModelFile file = io::parse_model(model_text(n, "FV12", "  - {set: all, dofs: [UX, UY, RZ]}\n"), "FV12");
  linalg::EigenOptions o;
  o.count = 10;
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(file.model, o);
  EXPECT_TRUE(a.result.converged) << a.result.message;
  const Eigen::VectorXd f = a.result.frequencies_hz();
  std::array<double, 7> out{};
  if (f.size() < 10) {
    ADD_FAILURE() << "FV12 " << n << " x " << n << ": " << f.size() << " modes";
    return out;
  }
  EXPECT_LT(f(2), 1e-3) << "three rigid modes expected";
  EXPECT_GT(f(3), 1.0) << "only three rigid modes expected";
  for (size_t k = 0; k < 7; ++k) out[k] = f(static_cast<Eigen::Index>(k) + 3);
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
  const io::ModelFile file =
      io::parse_model(model_text(4, "FV16", "  - {set: root, dofs: [UX, UY, UZ, RY]}\n"), "FV16");
  linalg::EigenOptions o;
  o.count = 6;
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(file.model, o);
  ASSERT_TRUE(a.result.converged) << a.result.message;
  const Eigen::VectorXd f = a.result.frequencies_hz();
  const std::array<double, 6> target{0.421, 1.029, 2.582, 3.306, 3.753, 6.555};
  const std::array<double, 6> tolerance{0.01, 0.01, 0.01, 0.01, 0.01, 0.01};
  check("FV16", std::span<const double>(f.data(), static_cast<size_t>(f.size())), target, tolerance, 1, "default 4x4",
        "target");
}

}  // namespace
}  // namespace rigflex
