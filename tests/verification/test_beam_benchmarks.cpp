// NAFEMS's beam benchmarks FV4 and FV6 at their meshes, read from model
// files as a user writes them (beams with no `theory`, so the default
// Timoshenko beam with rotary inertia is what the default cases check).
// E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3 throughout.
//
// FV4, cantilever with off-centre point masses (NAFEMS R0015; targets as
// quoted in Altair's OS-V 0410 and ANSYS's VMP09-T4): 1.723, 1.727, 7.413,
// 9.972, 18.155, 26.957 Hz; 5 beam elements, the masses (10000 kg and
// 1000 kg, no rotary inertia of their own) on rigid links at the tip. The
// dimensions are not in any source read here: L = 10 m, a solid circle of
// d = 0.5 m, the masses 2 m either side of the tip across the beam are a
// reconstruction - the only offsets in a scan of 0.5-3 m that fit all six
// targets, and with them the Euler-Bernoulli beam with the sections' rotary
// inertia reproduces every target to within 0.06 % (below). The targets
// leave shear out; at L/d = 20 the default Timoshenko beam lies 0.04-0.91 %
// below them (the second bending pair, modes 5-6, the most).
//
// FV6, the free thin ring (NAFEMS R0015 Test 6; Krysl's FinEtools tutorial
// and Altair's SS-V 2080 quote the data and both columns): mean radius
// R = 1 m, solid circle d = 0.1 m. Targets for the pairs of modes 7-16:
// 52.29, 53.97, 149.7, 152.4, 288.3 Hz (a sixth pair, 288.3, repeats the
// fifth's and is left out: the 20 chords that give the other five put it
// at 291.9 Hz, and the ring's own solution without shear at 288.0). Those
// targets are what 20 straight Euler-Bernoulli elements with rotary
// inertia give - measured here to 0.03 % - not the ring's own solution,
// which those 20 chords overestimate by 1.2 %. The ring's own solution is
// exact in closed form: each mode is one harmonic cos(n theta), so the
// ring's energies reduce to a 2 x 2 (Euler-Bernoulli) or 3 x 3 (Timoshenko)
// eigenproblem per harmonic, derived below; the straight elements converge
// to it as h^2 (1.9e-4 at 160 elements, measured).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

// Its own namespace: the suite builds as one unit, beside the plates' kE.
namespace rigflex::beam_benchmarks {
namespace {

constexpr double kE = 2.0e11, kNu = 0.3, kRho = 8000.0;

void expect_within(const char* what, double f, double reference, double tolerance) {
  const double error = f / reference - 1.0;
  std::printf("  %s: %.4f Hz, reference %.4f Hz, %+.3f %%\n", what, f, reference, 100.0 * error);
  EXPECT_LT(std::abs(error), tolerance) << what;
}

// ---------------------------------------------------------------- FV4

// `theory` is a beam key and its value, or empty for the default.
std::string fv4_model(const std::string& theory) {
  std::ostringstream s;
  s << "name: FV4\nmaterials:\n  steel: {E: " << kE << ", nu: " << kNu << ", rho: " << kRho << "}\n"
    << "beam_sections:\n  bar: {material: steel, shape: circle, diameter: 0.5}\n"
    << "members:\n  - {id: beam, from: [0, 0, 0], to: [10, 0, 0], elements: 5, section: bar" << theory << "}\n"
    << "nodes:\n  - [101, 10, 2, 0]\n  - [102, 10, -2, 0]\n"
    << "point_masses:\n  - {id: heavy, at: [10, 2, 0], mass: 10000}\n  - {id: light, at: [10, -2, 0], mass: 1000}\n"
    << "couplings:\n  - {id: arms, reference_at: [10, 0, 0], nodes: [101, 102], dofs: all}\n"
    << "supports:\n  - {at: [0, 0, 0], dofs: all}\n";
  return s.str();
}

constexpr std::array<double, 6> kFv4Targets{1.723, 1.727, 7.413, 9.972, 18.155, 26.957};

// The targets are printed to four digits (+-0.03 % at 1.723 Hz); five
// cubic elements leave the second bending pair about 0.06 % high (measured
// +0.057 % on mode 6). 0.1 % holds the sum, and fails on the sections'
// rotary inertia left out (+0.16 % on mode 6, measured) or a mass off its
// arm.
TEST(NafemsFv4, EulerBernoulliBeamsReproduceTheTargets) {
  const Eigen::VectorXd f = test::model_frequencies(fv4_model(", theory: euler-bernoulli"), "FV4", 6);
  ASSERT_EQ(f.size(), 6);
  for (int k = 0; k < 6; ++k)
    expect_within(("FV4 Euler-Bernoulli mode " + std::to_string(k + 1)).c_str(), f(k), kFv4Targets[k], 1e-3);
}

// The default at the prescribed mesh within 1 % of the targets (measured
// -0.04 .. -0.91 %), every mode below the Euler-Bernoulli beam's: shear
// only softens.
TEST(NafemsFv4, TheDefaultBeamWithinOnePercentBelowTheShearRigidOne) {
  const Eigen::VectorXd f = test::model_frequencies(fv4_model(""), "FV4", 6);
  const Eigen::VectorXd rigid = test::model_frequencies(fv4_model(", theory: euler-bernoulli"), "FV4", 6);
  ASSERT_EQ(f.size(), 6);
  ASSERT_EQ(rigid.size(), 6);
  for (int k = 0; k < 6; ++k) {
    expect_within(("FV4 default mode " + std::to_string(k + 1)).c_str(), f(k), kFv4Targets[k], 1e-2);
    EXPECT_LT(f(k), rigid(k)) << "mode " << k + 1;
  }
}

// ---------------------------------------------------------------- FV6

// The ring as `elements` straight beams between points on the circle.
std::string fv6_model(int elements, const std::string& beam_keys) {
  std::ostringstream s;
  s.precision(17);
  s << "name: FV6\nmaterials:\n  steel: {E: " << kE << ", nu: " << kNu << ", rho: " << kRho << "}\n"
    << "beam_sections:\n  bar: {material: steel, shape: circle, diameter: 0.1}\nnodes:\n";
  for (int i = 0; i < elements; ++i) {
    const double a = 2.0 * std::numbers::pi * i / elements;
    s << "  - [" << i + 1 << ", " << std::cos(a) << ", " << std::sin(a) << ", 0]\n";
  }
  s << "beams:\n";
  for (int i = 0; i < elements; ++i)
    s << "  - {id: b" << i + 1 << ", nodes: [" << i + 1 << ", " << (i + 1) % elements + 1 << "], section: bar"
      << beam_keys << "}\n";
  return s.str();
}

// Modes 7-18 (six pairs after the six rigid ones), Hz.
Eigen::VectorXd ring_frequencies(int elements, const std::string& beam_keys) {
  const Eigen::VectorXd f = test::elastic_modes(
      test::model_frequencies(fv6_model(elements, beam_keys), "FV6, " + std::to_string(elements) + " elements", 18), 6,
      10.0);
  return f.size() == 12 ? f : Eigen::VectorXd::Zero(12);
}

// The ring's lowest frequency of harmonic n, Hz, in closed form. Radial
// (in-plane) w = W cos, tangential v = V sin, the section's rotation
// psi = Psi sin; out of the plane u = w_z / R = U cos, twist phi = Phi cos,
// the section's rotation about the radius psi = Psi sin. Strains per unit
// amplitude (theta measured along the ring; the energies of a curved beam
// of radius R, zero for all six rigid motions):
//   in-plane:     stretch (n V + W)/R, shear Psi - (V + n W)/R, bending n Psi/R
//   out-of-plane: bending (Phi - n Psi)/R, twist (Psi - n Phi)/R, shear n U + Psi
// Kinetic: rho A (W^2 + V^2) + rho I Psi^2 in the plane; rho A R^2 U^2 +
// rho J Phi^2 + rho I Psi^2 out of it. Euler-Bernoulli holds the shear at
// zero: Psi = (V + n W)/R in the plane, Psi = -n U out of it. Solved as
// the largest eigenvalue of L^-1 M L^-T (K = L L', positive definite for
// n >= 2), so inertia left out (a singular M) needs no special case.
struct Ring {
  double A, I, J;
  double shear_area;           // 0: rigid in shear
  bool rotary_inertia = true;  // rho I, rho J of the sections
};

double ring_frequency(int n, bool in_plane, const Ring& r) {
  const double R = 1.0, G = kE / (2.0 * (1.0 + kNu));
  const double rotary = r.rotary_inertia ? 1.0 : 0.0;
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero(), M = Eigen::Matrix3d::Zero();
  auto add = [&](double stiffness, const Eigen::Vector3d& strain) { K += stiffness * strain * strain.transpose(); };
  Eigen::MatrixXd T = Eigen::Matrix3d::Identity();  // the three amplitudes from the free ones
  if (in_plane) {                                   // [W, V, Psi]
    add(kE * r.A, Eigen::Vector3d(1.0 / R, n / R, 0.0));
    add(G * r.shear_area, Eigen::Vector3d(-n / R, -1.0 / R, 1.0));
    add(kE * r.I, Eigen::Vector3d(0.0, 0.0, n / R));
    M.diagonal() << kRho * r.A, kRho * r.A, rotary * kRho * r.I;
    if (r.shear_area == 0) T = (Eigen::Matrix<double, 3, 2>() << 1, 0, 0, 1, n / R, 1.0 / R).finished();
  } else {  // [U, Phi, Psi]
    add(kE * r.I, Eigen::Vector3d(0.0, 1.0 / R, -n / R));
    add(G * r.J, Eigen::Vector3d(0.0, -n / R, 1.0 / R));
    add(G * r.shear_area, Eigen::Vector3d(n, 0.0, 1.0));
    M.diagonal() << kRho * r.A * R * R, rotary * kRho * r.J, rotary * kRho * r.I;
    if (r.shear_area == 0) T = (Eigen::Matrix<double, 3, 2>() << 1, 0, 0, 1, -n, 0).finished();
  }
  const Eigen::LLT<Eigen::MatrixXd> L(T.transpose() * K * T);
  Eigen::MatrixXd S = L.matrixL().solve(T.transpose() * M * T);
  S = L.matrixL().solve(S.transpose().eval());  // L^-1 M L^-T
  const double mu = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  return std::sqrt(1.0 / mu) / (2.0 * std::numbers::pi);
}

Ring fv6_ring(bool with_shear, bool rotary_inertia) {
  const double d = 0.1, A = std::numbers::pi * d * d / 4.0, I = std::numbers::pi * std::pow(d, 4) / 64.0;
  const double cowper = 6.0 * (1.0 + kNu) / (7.0 + 6.0 * kNu);  // the beam's own shear coefficient for a circle
  return {A, I, 2.0 * I, with_shear ? cowper * A : 0.0, rotary_inertia};
}

// The six pairs in the order the models give them: out-of-plane and
// in-plane for n = 2, 3, 4.
std::array<double, 6> ring_solution(const Ring& r) {
  std::array<double, 6> f{};
  for (int n = 2; n <= 4; ++n) {
    f[2 * (n - 2)] = ring_frequency(n, false, r);
    f[2 * (n - 2) + 1] = ring_frequency(n, true, r);
  }
  return f;
}

// The closed form itself: without shear and the sections' inertia it is
// the classical thin ring (Blevins, Formulas for Natural Frequency and Mode
// Shape, table 4.16; the reference column of SolidWorks's and Krysl's FV6:
// 51.849, 53.382, 148.77, 150.99, 286.98, 289.51 Hz). Out of the plane
// that formula is exact for those assumptions: 1e-4 covers its printed
// digits. In the plane it assumes an inextensible ring, which the closed
// form does not: 0.2 % (measured 0.08-0.11 %).
TEST(NafemsFv6, TheRingSolutionReducesToTheClassicalThinRing) {
  const std::array<double, 6> classical{51.849, 53.382, 148.77, 150.99, 286.98, 289.51};
  const std::array<double, 6> f = ring_solution(fv6_ring(false, false));
  for (int k = 0; k < 6; ++k)
    expect_within(("thin ring, pair " + std::to_string(k + 1)).c_str(), f[k], classical[k], k % 2 ? 2e-3 : 1e-4);
}

// NAFEMS's targets are 20 chords' Euler-Bernoulli values: reproduced to
// their four printed digits (+-0.03 %; measured within 0.03 %).
TEST(NafemsFv6, TwentyEulerBernoulliChordsReproduceTheTargets) {
  const Eigen::VectorXd f = ring_frequencies(20, ", theory: euler-bernoulli");
  const std::array<double, 5> target{52.29, 53.97, 149.7, 152.4, 288.3};
  for (int k = 0; k < 5; ++k)
    for (int member = 0; member < 2; ++member)
      expect_within(("FV6 20 chords, modes " + std::to_string(7 + 2 * k) + "-" + std::to_string(8 + 2 * k)).c_str(),
                    f(2 * k + member), target[k], 5e-4);
}

// The default (Timoshenko, rotary inertia) and Euler-Bernoulli beams
// against the ring's own solution. Chords converge as h^2: measured
// +1.9e-4 .. +2.1e-4 at 160 elements on every mode and about 4 x that at
// 80; 4e-4 at 160 holds that with room and fails on a missing rotary or
// torsional inertia (0.1-0.5 %) or a wrong shear coefficient (Cowper's
// against 5/6 moves n = 4 by 0.1 %).
TEST(NafemsFv6, TheBeamsConvergeToTheRingsOwnSolution) {
  for (const bool shear : {true, false}) {
    const std::array<double, 6> exact = ring_solution(fv6_ring(shear, true));
    const Eigen::VectorXd coarse = ring_frequencies(80, shear ? "" : ", theory: euler-bernoulli");
    const Eigen::VectorXd fine = ring_frequencies(160, shear ? "" : ", theory: euler-bernoulli");
    for (int k = 0; k < 6; ++k)
      for (int member = 0; member < 2; ++member) {
        const int mode = 2 * k + member;
        const std::string what =
            std::string(shear ? "default" : "Euler-Bernoulli") + " 160 chords, mode " + std::to_string(7 + mode);
        expect_within(what.c_str(), fine(mode), exact[k], 4e-4);
        // h^2: halving the chord quarters the error (3-5 x allows the
        // next term).
        const double ratio = (coarse(mode) / exact[k] - 1.0) / (fine(mode) / exact[k] - 1.0);
        EXPECT_GT(ratio, 3.0) << what;
        EXPECT_LT(ratio, 5.0) << what;
      }
  }
}

}  // namespace
}  // namespace rigflex::beam_benchmarks
