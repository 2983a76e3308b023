// Solid elements on NAFEMS FV52 (simply supported thick square plate,
// 10 m x 10 m x 1 m, E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3, UZ = 0 along
// the four edges of the lower face; three in-plane rigid-body modes, so the
// targets are modes 4-10), at the benchmark's prescribed meshes: hex8 on
// 8 x 8 x 3, hex20 on 4 x 4 x 1 (it prescribes none for tetrahedra; tet10 is
// checked against CalculiX's C3D10 matrices below and in bench/, table in
// docs/fe-core.md).
//
// What the references are:
//  * NAFEMS R0015's targets are thick-plate values. A solid supported along a
//    line has a stress singularity there, so its frequencies do not converge
//    to them: they keep falling slowly as the mesh is refined (hex20, mode 4:
//    44.80 Hz at 4 x 4 x 1, 43.72 at 8 x 8 x 2, 43.24 at 16 x 16 x 4 against
//    45.897). The benchmark therefore judges elements at its own meshes.
//  * Altair publishes OptiStruct's ratios to the targets at exactly these
//    meshes (OS-V 0455: HEXA8 8x8x3, HEXA20 4x4x1), to four digits: an
//    independent code on the same discretization. rigflex must reproduce them
//    to their rounding (5e-5) plus the targets' own (5 digits, < 1.2e-5):
//    1e-4.
//  * CalculiX: its stored K and M against rigflex's (all three types, below),
//    and the FV52 frequencies with hex20 against C3D20 to 1e-5 (measured
//    2e-7); why not the other two, see there.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "fe/assembly.hpp"
#include "fe/meshers.hpp"
#include "reduction/modal_analysis.hpp"
#include "require_ccx.hpp"
#include "verification/calculix.hpp"
#include "verification/nafems_fv52.hpp"

namespace rigflex {
namespace {
namespace fs = std::filesystem;

constexpr int kModes = 10;
using verification::kFv52TargetsHz;
using verification::nafems_fv52;

Eigen::VectorXd rigflex_modes(const fe::Model& m) {
  linalg::EigenOptions options;
  options.count = kModes;
  options.shift = -std::pow(2 * M_PI * 10.0, 2);  // below the three rigid-body modes
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(m, options);
  EXPECT_TRUE(a.result.converged) << a.result.message;
  // Rigid-body modes read ~1e-3 in the residual ratio by rounding alone
  // (linalg/eigen_solver.hpp); the backward error holds for all pairs.
  EXPECT_LT(a.result.residuals.tail(kModes - 3).maxCoeff(), 1e-8);
  EXPECT_LT(a.result.backward_errors.maxCoeff(), 1e-12);
  EXPECT_LT(a.result.orthogonality_error, 1e-8);
  return a.result.frequencies_hz();
}

struct Case {
  const char* element;
  int n, nz;
  std::vector<double> optistruct;  // published ratios to the targets, modes 4-10
};

const std::vector<Case> kCases{
    {"hex8", 8, 3, {0.9874, 1.0413, 1.0413, 1.0322, 1.0164, 1.0164, 1.0164}},
    {"hex20", 4, 1, {0.9760, 1.0101, 1.0101, 1.0072, 1.0017, 1.0022, 1.0022}},
};

TEST(SolidBenchmark, NafemsFv52AtThePrescribedMeshes) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.element);
    const Eigen::VectorXd f = rigflex_modes(nafems_fv52(c.element, c.n, c.nz));
    ASSERT_EQ(f.size(), kModes);
    for (int k = 0; k < 3; ++k) EXPECT_LT(f(k), 1e-3) << "mode " << k + 1 << " should be an in-plane rigid-body mode";
    for (size_t i = 0; i < kFv52TargetsHz.size(); ++i) {
      const double ratio = f(static_cast<Eigen::Index>(i) + 3) / kFv52TargetsHz[i];
      std::printf("  FV52 %-5s %dx%dx%d mode %2zu: %9.3f Hz, target %8.3f, ratio %.4f%s\n", c.element, c.n, c.n, c.nz,
                  i + 4, f(static_cast<Eigen::Index>(i) + 3), kFv52TargetsHz[i], ratio,
                  ("  (OptiStruct " + std::to_string(c.optistruct[i]).substr(0, 6) + ")").c_str());
      EXPECT_NEAR(ratio, c.optistruct[i], 1e-4) << "mode " << i + 4;
    }
  }
}

// Frequencies on the FV52 mesh with hex20 against C3D20 (identical matrices,
// see below): to ccx's eigen tolerance. Not asserted for the other two:
// ccx's C3D10 mass is not the consistent one (its M differs by 25 % in
// norm; frequencies up to +0.7 %), and ccx 2.20's *FREQUENCY with C3D8I
// returns frequencies 2.5-9 % below the eigenvalues of its own stored K and
// M, which are rigflex's hex8 matrices to 1e-14 on this rectangular mesh
// (its manual warns that C3D8I's internal DOFs carry no mass).
TEST(SolidBenchmark, Fv52Hex20FrequenciesAgreeWithCalculix) {
  REQUIRE_CCX("the solid elements' CalculiX cross-check");
  for (const Case& c : {kCases[1]}) {  // hex20
    SCOPED_TRACE(c.element);
    const fe::Model m = nafems_fv52(c.element, c.n, c.nz);
    const Eigen::VectorXd f = rigflex_modes(m);
    const fs::path dir =
        fs::temp_directory_path() / ("rigflex-ccx-fv52-" + std::string(c.element) + "-" + std::to_string(::getpid()));
    const verification::CalculixFrequencies r = verification::run_calculix_frequencies(m, kModes, dir);
    ASSERT_GE(static_cast<int>(r.frequencies_hz.size()), kModes);
    for (int k = 3; k < kModes; ++k) {
      std::printf("  FV52 %-5s mode %2d: rigflex %9.4f Hz, ccx %9.4f Hz\n", c.element, k + 1, f(k),
                  r.frequencies_hz[static_cast<size_t>(k)]);
      EXPECT_NEAR(r.frequencies_hz[static_cast<size_t>(k)] / f(k), 1.0, 1e-5) << "mode " << k + 1;
    }
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
  }
}

}  // namespace
}  // namespace rigflex

namespace rigflex {
namespace {

// The assembled matrices against ccx's stored K and M on the same nodes
// (C3D8I's internal DOFs condensed, as rigflex condenses them in the
// element), on a rectangular block and on a block of general hexahedra:
//   K: identical to rounding (1e-12) for all three on the rectangular block,
//      and for hex20 and tet10 on the general one. hex8 on general shapes is
//      not compared: rigflex maps the bubbles with Taylor's centre-Jacobian
//      correction, which its patch test needs (tests/fe); ccx's C3D8I
//      differs there by ~1.4 % in norm.
//   M: hex8 and hex20 identical on the rectangular block; on general shapes
//      ccx integrates with fewer points (inexact: 2x2x2 / 3x3x3) where rigflex
//      is exact (tests/fe checks mass and inertia), within 1e-3. ccx's C3D10
//      mass is not the consistent one (compared by total mass only).
struct BlockMatrices {
  Eigen::MatrixXd Kr, Mr, Kc, Mc;  // rigflex, ccx, on the model's translations
};

BlockMatrices block_matrices(const char* element, bool general) {
  fe::Model m;
  m.materials["steel"] = fe::Material{"steel", 2.0e11, 0.3, 8000.0};
  fe::NodeMerger merger(m);
  fe::SolidBlockSpec spec;
  spec.id = "block";
  if (general)
    spec.corners = {fe::Vec3(0, 0, 0),     fe::Vec3(2, 0.1, 0),   fe::Vec3(2.2, 1.3, 0.1), fe::Vec3(-0.1, 1, 0),
                    fe::Vec3(0.1, 0, 0.9), fe::Vec3(2.1, 0, 1.2), fe::Vec3(2, 1.1, 1),     fe::Vec3(0, 1.2, 1.1)};
  else
    spec.corners = {fe::Vec3(0, 0, 0), fe::Vec3(2, 0, 0), fe::Vec3(2, 1, 0), fe::Vec3(0, 1, 0),
                    fe::Vec3(0, 0, 1), fe::Vec3(2, 0, 1), fe::Vec3(2, 1, 1), fe::Vec3(0, 1, 1)};
  spec.nx = 2;
  spec.element = element;
  spec.material = "steel";
  fe::mesh_solid_block(m, merger, spec);
  fe::SpMat K, M;
  fe::assemble_full(m, K, M);
  const fs::path dir = fs::temp_directory_path() / ("rigflex-ccx-solid-matrices-" + std::string(element) +
                                                    (general ? "-general-" : "-box-") + std::to_string(::getpid()));
  const verification::CalculixMatrices c = verification::run_calculix_matrices(m, dir);
  std::vector<Eigen::Index> ours, theirs, internal;
  std::vector<bool> used(static_cast<size_t>(c.K.rows()), false);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    for (int d = 1; d <= 3; ++d) {
      const auto row = c.row_of(m.nodes[i].id, d);
      if (!row) throw std::runtime_error("ccx has no row for node " + std::to_string(m.nodes[i].id));
      ours.push_back(6 * static_cast<Eigen::Index>(i) + d - 1);
      theirs.push_back(*row);
      used[static_cast<size_t>(*row)] = true;
    }
  for (Eigen::Index r = 0; r < c.K.rows(); ++r)
    if (!used[static_cast<size_t>(r)]) internal.push_back(r);
  const Eigen::MatrixXd Kc = Eigen::MatrixXd(c.K), Mc = Eigen::MatrixXd(c.M);
  BlockMatrices b{Eigen::MatrixXd(K)(ours, ours), Eigen::MatrixXd(M)(ours, ours), Kc(theirs, theirs),
                  Mc(theirs, theirs)};
  if (!internal.empty())  // C3D8I's massless bubble DOFs
    b.Kc -= Kc(theirs, internal) * Kc(internal, internal).ldlt().solve(Kc(internal, theirs));
  fs::remove_all(dir);
  return b;
}

double rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

TEST(SolidBenchmark, MatricesAgreeWithCalculix) {
  REQUIRE_CCX("the solid elements' CalculiX matrix comparison");
  for (bool general : {false, true})
    for (const char* element : {"hex8", "hex20", "tet10"}) {
      SCOPED_TRACE(std::string(element) + (general ? " general" : " rectangular"));
      const BlockMatrices b = block_matrices(element, general);
      std::printf("  %-5s %-11s K rel. diff %.2e, M rel. diff %.2e\n", element, general ? "general" : "rectangular",
                  rel(b.Kc, b.Kr), rel(b.Mc, b.Mr));
      const bool hex8 = std::string(element) == "hex8", tet10 = std::string(element) == "tet10";
      if (!(general && hex8)) {
        EXPECT_LT(rel(b.Kc, b.Kr), 1e-12);
      }
      if (tet10) {
        // x-translation block: the total mass, ccx's way or rigflex's.
        EXPECT_NEAR(b.Mc(Eigen::seq(0, Eigen::last, 3), Eigen::seq(0, Eigen::last, 3)).sum() /
                        b.Mr(Eigen::seq(0, Eigen::last, 3), Eigen::seq(0, Eigen::last, 3)).sum(),
                    1.0, 1e-12);
      } else {
        EXPECT_LT(rel(b.Mc, b.Mr), general ? 1e-3 : 1e-12);
      }
    }
}

}  // namespace
}  // namespace rigflex
