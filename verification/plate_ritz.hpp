#pragma once
// An independent reference for plate benchmarks: the natural frequencies of
// a clamped parallelogram plate by the Ritz method on Mindlin-Reissner plate
// theory (the theory rigflex's shells discretize), with no finite element
// in it. The deflection and both rotations are each expanded in products of
// (1 - s^2) P_i(s) and (1 - t^2) P_j(t) (P_i Legendre) on the plate's
// affine map from [-1, 1]^2, which vanish on the clamped edges; the energies
// are integrated exactly by Gauss-Legendre rules, so the frequencies are
// upper bounds of the plate theory's that converge spectrally with `terms`
// (the clamped rhombic plates of NAFEMS FV15 / FV22: five digits at 16).
// Shear correction 5/6 and rotary inertia rho t^3 / 12, as in fe/'s shells.
// For a thin plate the result tends to Kirchhoff's: the clamped square at
// a/t = 1000 gives Leissa's 35.985, 73.394, 108.22, 131.58, 132.20 (lambda
// = omega a^2 sqrt(rho t / D)) to 1e-4 (tests/verification/test_plate_ritz.cpp).
#include <numbers>
#include <vector>

namespace rigflex::verification {

struct ParallelogramPlate {
  double side_a = 10.0;               // m, the edge along x
  double side_b = 10.0;               // m, the edge at `angle` from x
  double angle = std::numbers::pi / 2;  // rad, between the two edges (pi / 2: a rectangle)
  double thickness = 0.05;            // m
  double E = 2.0e11, nu = 0.3, rho = 8000.0;
};

// The lowest `count` natural frequencies in Hz, clamped on all four edges,
// with `terms` x `terms` functions per field (3 terms^2 unknowns, dense).
// std::invalid_argument for a plate that is not one or count > 3 terms^2.
std::vector<double> clamped_plate_frequencies_hz(const ParallelogramPlate& plate, int count, int terms = 16);

}  // namespace rigflex::verification
