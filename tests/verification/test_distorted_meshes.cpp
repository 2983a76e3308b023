// NAFEMS benchmarks of elements on distorted meshes, read from model files
// as a user writes them (meshers with the benchmark's divisions and no
// `order`, so the meshers' default element is what is checked).
//
// FV15 and FV22 (NAFEMS R0015 / TNSB Rev. 3; targets as quoted in
// Altair's OS-V 0425 and 0435): a 10 m rhombic plate, 45 degree skew,
// E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3, clamped on all edges (w and
// both bending rotations), in-plane motion and drilling held everywhere.
// FV15 is thin (t = 0.05 m, prescribed mesh 12 x 12), FV22 thick (t = 1 m,
// 10 x 10). They test elements on distorted (parallelogram) meshes.
//
// Tolerances, per mode, against the targets. The targets themselves sit
// off the Mindlin plate's solution, which a Ritz solution of the plate with
// no element in it gives (verification/plate_ritz.hpp): FV15's targets
// +0.18..+1.47 % above it, FV22's -0.50..+2.19 % about it (checked below,
// TheDefaultShellConvergesToThePlatesOwnSolution); the default element
// converges to that solution from above (0.03 % off at 2x). So 1.5 % on
// every mode NAFEMS gives as a closed form: measured at most 1.16 %
// (FV15's fifth, where the target is 1.47 % above the plate) and 0.90 %
// (FV22's fourth). FV22's sixth target is no closed form but a
// higher-order element's result (NAFEMS's "H.O.E." value), 2.19 % above the
// plate: an unconverged mesh's frequency, which any converging element
// passes on its way down. It is checked as such: the default element at the
// prescribed mesh lies between the plate and that value (measured 0.32 %
// above the plate, 1.84 % below the target). MITC4 (`order: linear`) is
// checked at twice the prescribed mesh: within 3 % (measured +0.3 .. +2.6 %
// on FV15; at the prescribed mesh it is up to 16 % high, a stated limit).
//
// FV32, the cantilevered tapered membrane (NAFEMS R0015 / TNSB Rev. 3;
// its targets not re-read from the document here - the default element at
// 16 x 8 reproduces them to five digits): a trapezoid (0,0), (10,2),
// (10,3), (0,5) m, E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3,
// clamped along x = 0, in-plane modes (out-of-plane motion held), at the
// prescribed 8 x 4 mesh. Tolerance 1 %: its targets agree with the default
// element at 16 x 8 to 0.01 %; at 8 x 4 it measured at most +0.56 % (mode
// 5; MITC4 there +4.8 .. +8.9 % on modes 4-6).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"
#include "verification/plate_ritz.hpp"

namespace rigflex {
namespace {

struct Benchmark {
  const char* name;
  double thickness;
  int divisions;                    // the prescribed mesh, n x n
  std::array<double, 6> target;     // Hz
  std::array<double, 6> tolerance;  // relative, for the default element at the prescribed mesh
  std::array<bool, 6> element_result{};  // the target is a higher-order element's frequency, no closed form
};

const Benchmark kFv15{
    "FV15", 0.05, 12, {7.938, 12.835, 17.941, 19.133, 24.009, 27.922}, {0.015, 0.015, 0.015, 0.015, 0.015, 0.015}};
const Benchmark kFv22{"FV22",
                      1.0,
                      10,
                      {133.95, 201.41, 265.81, 283.68, 334.45, 386.62},
                      {0.015, 0.015, 0.015, 0.015, 0.015, 0.015},
                      {false, false, false, false, false, true}};

// The model file: the rhombus' corners, its edge nodes clamped by position.
std::string model_text(const Benchmark& b, int n, const std::string& order) {
  const double a = 10.0, c = a * std::cos(M_PI / 4.0), s = a * std::sin(M_PI / 4.0);
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "name: %s\nmaterials:\n  steel: {E: 2.0e11, nu: 0.3, rho: 8000}\nshell_sections:\n"
      "  plate: {material: steel, thickness: %g}\nshell_patches:\n"
      "  - {id: plate, corners: [[0, 0, 0], [%.17g, 0, 0], [%.17g, %.17g, 0], [%.17g, %.17g, 0]], "
      "divisions: [%d, %d], %ssection: plate}\n"
      "node_sets:\n  all: {box: [[-1, -1, -1], [20, 20, 1]]}\nsupports:\n  - {set: all, dofs: [UX, UY, RZ]}\n",
      b.name, b.thickness, a, a + c, s, c, s, n, n, order.empty() ? "" : ("order: " + order + ", ").c_str());
  std::string text = buf;
  const int m = order == "linear" ? n : 2 * n;  // the grid of the element's nodes
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j) {
      if (i != 0 && i != m && j != 0 && j != m) continue;
      const double u = static_cast<double>(i) / m, v = static_cast<double>(j) / m;
      std::snprintf(buf, sizeof buf, "  - {at: [%.17g, %.17g, 0], dofs: [UZ, RX, RY]}\n", u * a + v * c, v * s);
      text += buf;
    }
  return text;
}

Eigen::VectorXd frequencies(const Benchmark& b, int n, const std::string& order) {
  const io::ModelFile file = io::parse_model(model_text(b, n, order), b.name);
  linalg::EigenOptions o;
  o.count = 6;
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(file.model, o);
  EXPECT_TRUE(a.result.converged) << a.result.message;
  return a.result.frequencies_hz();
}

// f against `reference` (the benchmark's targets, or another solution named
// `against`), mode by mode within each mode's tolerance.
void check(const Benchmark& b, const Eigen::VectorXd& f, const std::array<double, 6>& tolerance, const char* what,
           const std::array<double, 6>& reference, const char* against) {
  ASSERT_EQ(f.size(), 6);
  for (size_t k = 0; k < 6; ++k) {
    const Eigen::Index m = static_cast<Eigen::Index>(k);
    const double error = f(m) / reference[k] - 1.0;
    std::printf("  %s %s mode %zu: %.4f Hz, %s %.4f Hz, %+.2f %%\n", b.name, what, k + 1, f(m), against, reference[k],
                100.0 * error);
    EXPECT_LT(std::abs(error), tolerance[k]) << b.name << " " << what << " mode " << k + 1;
  }
}

void check(const Benchmark& b, const Eigen::VectorXd& f, const std::array<double, 6>& tolerance, const char* what) {
  check(b, f, tolerance, what, b.target, "target");
}

std::array<double, 6> plate_solution(const Benchmark& b);

TEST(DistortedMeshes, TheDefaultShellMeetsFv15AndFv22AtTheirMeshes) {
  for (const Benchmark& b : {kFv15, kFv22}) {
    const Eigen::VectorXd f = frequencies(b, b.divisions, "");
    ASSERT_EQ(f.size(), 6);
    const std::array<double, 6> plate = plate_solution(b);
    for (size_t k = 0; k < 6; ++k) {
      const double hz = f(static_cast<Eigen::Index>(k)), error = hz / b.target[k] - 1.0;
      std::printf("  %s default 1x mode %zu: %.4f Hz, target %.4f Hz%s, %+.2f %%\n", b.name, k + 1, hz, b.target[k],
                  b.element_result[k] ? " (an element's)" : "", 100.0 * error);
      if (!b.element_result[k]) {
        EXPECT_LT(std::abs(error), b.tolerance[k]) << b.name << " mode " << k + 1;
        continue;
      }
      EXPECT_GT(hz, plate[k]) << b.name << " mode " << k + 1 << ": below the converged plate";
      EXPECT_LT(hz, b.target[k]) << b.name << " mode " << k + 1 << ": above the coarser element's result";
    }
  }
}

// Against the plate's own solution: the Ritz reference on the same plate
// theory (verification/plate_ritz.hpp, converged to 1.5e-5), which the
// benchmark's targets miss by up to 1.47 % (FV15) and 2.19 % (FV22's sixth).
// Tolerances: at the prescribed meshes 0.5 % (measured at most +0.29 % on
// FV15, +0.39 % on FV22's fifth; the element with its centre condensed
// statically read +0.88 % on FV22's sixth, the centre's inertia left out);
// at twice the meshes 0.05 % (measured at most 0.03 %: the error falls
// 10-15 x per halving, near the h^4 of a quadratic element).
std::array<double, 6> plate_solution(const Benchmark& b) {
  verification::ParallelogramPlate p;
  p.angle = M_PI / 4.0;
  p.thickness = b.thickness;
  const std::vector<double> hz = verification::clamped_plate_frequencies_hz(p, 6);
  std::array<double, 6> exact{};
  for (size_t k = 0; k < 6; ++k) {
    exact[k] = hz[k];
    std::printf("  %s mode %zu: plate %.4f Hz, the target %+.2f %% off it\n", b.name, k + 1, exact[k],
                100.0 * (b.target[k] / exact[k] - 1.0));
  }
  return exact;
}

TEST(DistortedMeshes, TheDefaultShellConvergesToThePlatesOwnSolution) {
  const auto within = [](double tolerance) {
    std::array<double, 6> t{};
    t.fill(tolerance);
    return t;
  };
  for (const Benchmark& b : {kFv15, kFv22}) {
    const std::array<double, 6> exact = plate_solution(b);
    check(b, frequencies(b, b.divisions, ""), within(0.005), "default 1x", exact, "plate");
    check(b, frequencies(b, 2 * b.divisions, ""), within(5e-4), "default 2x", exact, "plate");
  }
}

TEST(DistortedMeshes, TheDefaultShellMeetsFv32AtItsMesh) {
  const std::string text = R"(name: FV32
materials:
  steel: {E: 2.0e11, nu: 0.3, rho: 8000}
shell_sections:
  membrane: {material: steel, thickness: 0.1}
shell_patches:
  - {id: p, corners: [[0, 0, 0], [10, 2, 0], [10, 3, 0], [0, 5, 0]], divisions: [8, 4], section: membrane}
node_sets:
  all: {box: [[-1, -1, -1], [11, 6, 1]]}
  root: {line: [[0, 0, 0], [0, 5, 0]]}
supports:
  - {set: all, dofs: [UZ, RX, RY]}
  - {set: root, dofs: all}
)";
  const Benchmark fv32{"FV32", 0.1, 8, {44.623, 130.03, 162.70, 246.05, 379.90, 391.44}, {}};
  linalg::EigenOptions o;
  o.count = 6;
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(io::parse_model(text, "FV32").model, o);
  ASSERT_TRUE(a.result.converged) << a.result.message;
  check(fv32, a.result.frequencies_hz(), {0.01, 0.01, 0.01, 0.01, 0.01, 0.01}, "default 1x");
}

TEST(DistortedMeshes, Mitc4IsWithin3PercentAtTwiceTheFv15Mesh) {
  const std::array<double, 6> three{0.03, 0.03, 0.03, 0.03, 0.03, 0.03};
  check(kFv15, frequencies(kFv15, 2 * kFv15.divisions, "linear"), three, "MITC4 2x");
}

}  // namespace
}  // namespace rigflex
