// Guyan and Craig-Bampton as pure functions of matrices, against the
// closed-form and printed cases of shared/verification and dense algebra.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "fe/assembly.hpp"
#include "fe/dof.hpp"
#include "fe/meshers.hpp"
#include "fe/node_merger.hpp"
#include "reduction/component_modes.hpp"
#include "support/frame_models.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

using reduction::ComponentModeOptions;
using reduction::ReducedMatrices;
using reduction::ReductionMethod;
using linalg::SpMat;

SpMat sparse(const Eigen::MatrixXd& A) { return A.sparseView(); }

Eigen::Index free_dof(const fe::Model& m, const fe::AssembledSystem& s, fe::NodeId node, fe::Dof d) {
  return s.dofs.full_to_free[m.node_index(node) * 6 + static_cast<size_t>(d)];
}

std::vector<Eigen::Index> joint_translations(const fe::Model& m, const fe::AssembledSystem& sys,
                                             const std::string& set) {
  std::vector<Eigen::Index> b;
  for (fe::NodeId n : m.node_set(set))
    for (fe::Dof d : {fe::Dof::UX, fe::Dof::UY, fe::Dof::UZ}) b.push_back(free_dof(m, sys, n, d));
  return b;
}

ComponentModeOptions craig_bampton(int modes) {
  ComponentModeOptions o;
  o.method = ReductionMethod::craig_bampton;
  o.modes = modes;
  return o;
}

// Case B of RED-GUYAN: a 4-DOF axial spring chain condensed onto its ends.
TEST(Guyan, SpringChainMatchesClosedForm) {
  const YAML::Node c = test::verification_case("reduction_guyan_cantilever_and_spring_chain.yaml");
  const double s = c["case_B"]["parameters"]["s_N_per_m"].as<double>();
  Eigen::MatrixXd K(4, 4);
  K << s, -s, 0, 0, -s, 2 * s, -s, 0, 0, -s, 2 * s, -s, 0, 0, -s, 2 * s;
  const SpMat M = sparse(Eigen::MatrixXd::Identity(4, 4));
  ComponentModeOptions o;
  // variant_001: DOF 4 grounded through one more spring.
  ReducedMatrices r = reduction::reduce_component(sparse(K), M, {0, 3}, o);
  ASSERT_TRUE(r.ok) << r.message;
  Eigen::Matrix2d expected;
  expected << s / 3, -s / 3, -s / 3, s + s / 3;
  // Three condensation steps on integers times s: exact to a few roundings.
  EXPECT_LE((r.K - expected).cwiseAbs().maxCoeff(), 1e-14 * s * 8);
  // variant_002: the free-free chain, reduced stiffness AE/(3l) between the ends.
  K(3, 3) = s;
  r = reduction::reduce_component(sparse(K), M, {0, 3}, o);
  ASSERT_TRUE(r.ok) << r.message;
  expected << s / 3, -s / 3, -s / 3, s / 3;
  EXPECT_LE((r.K - expected).cwiseAbs().maxCoeff(), 1e-14 * s * 8);
}

struct Cantilever {
  fe::Model model;
  fe::NodeId tip = 0;
  double L = 0, E = 0, I = 0, rhoA = 0;
};

// Case A of RED-GUYAN: an Euler-Bernoulli cantilever of n elements.
Cantilever cantilever(int elements) {
  const YAML::Node c = test::verification_case("reduction_guyan_cantilever_and_spring_chain.yaml")["case_A"];
  Cantilever b;
  b.L = c["geometry"]["length_m"].as<double>();
  const double side = c["geometry"]["section"]["b_m"].as<double>();
  b.E = c["material"]["E_Pa"].as<double>();
  const double rho = c["material"]["rho_kg_m3"].as<double>();
  b.model.materials["steel"] = {"steel", b.E, c["material"]["nu"].as<double>(), rho};
  b.model.beam_sections["sq"] = test::rect_section("sq", side, side);
  b.I = side * side * side * side / 12;
  b.rhoA = rho * side * side;
  fe::NodeMerger merger(b.model);
  fe::MemberSpec ms;
  ms.id = "beam";
  ms.to = {b.L, 0, 0};
  ms.elements = elements;
  ms.section = "sq";
  ms.theory = fe::BeamTheory::EulerBernoulli;
  ms.rotary_inertia = false;
  const auto nodes = fe::mesh_member(b.model, merger, ms);
  test::fix(b.model, nodes.front(), {0, 1, 2, 3, 4, 5});
  b.tip = nodes.back();
  return b;
}

TEST(Guyan, CantileverOntoTipIsTheSingleElement) {
  const Cantilever b = cantilever(20);
  const fe::AssembledSystem sys = fe::assemble(b.model);
  const std::vector<Eigen::Index> tip{free_dof(b.model, sys, b.tip, fe::Dof::UZ),
                                      free_dof(b.model, sys, b.tip, fe::Dof::RY)};
  const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, tip, {});
  ASSERT_TRUE(r.ok) << r.message;
  // The Guyan shapes of a Hermite mesh are the exact static cubics, so the
  // reduced matrices are the one-element matrices whatever the mesh
  // (derived_here in the case file). RY = -dw/dx flips the coupling sign.
  const double L = b.L, k = b.E * b.I / (L * L * L), m = b.rhoA * L / 420;
  Eigen::Matrix2d Ke, Me;
  Ke << 12 * k, 6 * L * k, 6 * L * k, 4 * L * L * k;
  Me << 156 * m, 22 * L * m, 22 * L * m, 4 * L * L * m;
  // Condensing 120 DOFs of a matrix with condition ~1e8 leaves ~1e-9.
  EXPECT_LE((r.K - Ke).cwiseAbs().maxCoeff() / Ke.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((r.M - Me).cwiseAbs().maxCoeff() / Me.cwiseAbs().maxCoeff(), 1e-9);

  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(r.K, r.M);
  const YAML::Node c = test::verification_case("reduction_guyan_cantilever_and_spring_chain.yaml")["case_A"];
  const auto coeff = c["dimensionless_results"]["guyan_coefficients_c"].as<std::vector<double>>();
  for (int i = 0; i < 2; ++i) {
    const double ci = std::sqrt(es.eigenvalues()(i)) * std::sqrt(b.rhoA * std::pow(L, 4) / (b.E * b.I));
    // Printed to 6 significant digits.
    EXPECT_NEAR(ci / coeff[static_cast<size_t>(i)], 1.0, 2e-6) << "mode " << i + 1;
  }
  // And the printed Hz targets (derived from the same coefficients).
  const auto targets = test::verification_frequencies("reduction_guyan_cantilever_and_spring_chain.yaml");
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(std::sqrt(es.eigenvalues()(i)) / (2 * M_PI) / targets[static_cast<size_t>(i)], 1.0, 2e-5);
  }
}

TEST(Guyan, PortalWithMasslessMembersIsExact) {
  std::array<fe::NodeId, 2> corners{};
  const fe::Model m = test::portal_frame(2e-4, &corners);
  const fe::AssembledSystem sys = fe::assemble(m);
  std::vector<Eigen::Index> b;
  for (fe::NodeId n : corners)
    for (fe::Dof d : {fe::Dof::UX, fe::Dof::UY}) b.push_back(free_dof(m, sys, n, d));
  const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, b, {});
  ASSERT_TRUE(r.ok) << r.message;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(r.K, r.M);
  const double f1 = std::sqrt(es.eigenvalues()(0)) / (2 * M_PI);
  const double target = test::verification_frequencies("portal_frame_sway_closed_form.yaml")[0];
  // Exact up to the axial compliance of A = 1e3 m^2 (~1e-7) and the 7 printed digits.
  EXPECT_NEAR(f1 / target, 1.0, 1e-6);
  // The full model has no mass off the retained DOFs: the same eigenvalue up
  // to rounding, which the condition of K (~1e8 with A = 1e3 m^2) sets at
  // ~1e-8 relative for either computation.
  linalg::EigenOptions eo;
  eo.count = 1;
  const auto full = linalg::solve_lanczos(sys.K, sys.M, eo);
  ASSERT_TRUE(full.converged);
  EXPECT_NEAR(es.eigenvalues()(0) / full.eigenvalues(0), 1.0, 2e-8);
}

// Dense reference: T = [I; -K_ii^-1 K_ib] by LU on the permuted dense matrices.
TEST(Guyan, MatchesDenseSchurComplementAndKeepsStatics) {
  const fe::Model m = test::rig_fixed_frame(2);
  const fe::AssembledSystem sys = fe::assemble(m);
  const auto b = joint_translations(m, sys, "upper_joints");
  const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, b, {});
  ASSERT_TRUE(r.ok) << r.message;

  const Eigen::MatrixXd K(sys.K), M(sys.M);
  const Eigen::Index n = K.rows(), nb = static_cast<Eigen::Index>(b.size());
  std::vector<Eigen::Index> order = b;
  for (Eigen::Index j = 0; j < n; ++j)
    if (std::find(b.begin(), b.end(), j) == b.end()) order.push_back(j);
  Eigen::PermutationMatrix<Eigen::Dynamic> P(n);
  for (Eigen::Index k = 0; k < n; ++k) P.indices()(k) = static_cast<int>(order[static_cast<size_t>(k)]);
  const Eigen::MatrixXd Kp = P.transpose() * K * P, Mp = P.transpose() * M * P;
  Eigen::MatrixXd T(n, nb);
  T.topRows(nb).setIdentity();
  T.bottomRows(n - nb) = -Kp.bottomRightCorner(n - nb, n - nb).partialPivLu().solve(Kp.bottomLeftCorner(n - nb, nb));
  const Eigen::MatrixXd Kr = T.transpose() * Kp * T, Mr = T.transpose() * Mp * T;
  EXPECT_LE((r.K - Kr).cwiseAbs().maxCoeff() / Kr.cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE((r.M - Mr).cwiseAbs().maxCoeff() / Mr.cwiseAbs().maxCoeff(), 1e-10);
  // The kept basis expands reduced vectors onto all free DOFs.
  EXPECT_LE((r.basis - P * T).cwiseAbs().maxCoeff() / T.cwiseAbs().maxCoeff(), 1e-10);

  // Static exactness: the interface flexibility equals the full model's
  // (K^-1)_bb, by a dense inverse that shares nothing with the reduction.
  const Eigen::MatrixXd G = K.llt().solve(Eigen::MatrixXd::Identity(n, n));
  Eigen::MatrixXd Gbb(nb, nb);
  for (Eigen::Index i = 0; i < nb; ++i)
    for (Eigen::Index j = 0; j < nb; ++j) Gbb(i, j) = G(b[size_t(i)], b[size_t(j)]);
  const Eigen::MatrixXd Gr = r.K.llt().solve(Eigen::MatrixXd::Identity(nb, nb));
  EXPECT_LE((Gr - Gbb).cwiseAbs().maxCoeff() / Gbb.cwiseAbs().maxCoeff(), 1e-10);
}

TEST(CraigBampton, StructureAndFixedInterfaceModes) {
  const fe::Model m = test::rig_fixed_frame(4);
  const fe::AssembledSystem sys = fe::assemble(m);
  const auto b = joint_translations(m, sys, "upper_joints");
  const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, b, craig_bampton(8));
  ASSERT_TRUE(r.ok) << r.message;
  const Eigen::Index nb = 9;
  ASSERT_EQ(r.K.rows(), nb + 8);
  // Modal block: K = Omega^2 and M = I (M-normalized modes), uncoupled in K.
  const Eigen::MatrixXd Mqq = r.M.bottomRightCorner(8, 8);
  EXPECT_LE((Mqq - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(r.K.topRightCorner(nb, 8).cwiseAbs().maxCoeff(), 0.0);
  // The coupling that T' K T would have: Phi' (K_ib + K_ii Psi) = 0 is what
  // makes the zero block exact; check it on the basis.
  const Eigen::MatrixXd KT = sys.K * r.basis;
  const Eigen::MatrixXd coupling = r.basis.rightCols(8).transpose() * KT.leftCols(nb);
  EXPECT_LE(coupling.cwiseAbs().maxCoeff() / r.K.cwiseAbs().maxCoeff(), 1e-9);
  // Fixed-interface modes: the full model with the interface DOFs held.
  fe::Model held = m;
  for (fe::NodeId n : m.node_set("upper_joints")) test::fix(held, n, {0, 1, 2});
  const fe::AssembledSystem hs = fe::assemble(held);
  linalg::EigenOptions eo;
  eo.count = 8;
  const auto ref = linalg::solve_lanczos(hs.K, hs.M, eo);
  ASSERT_TRUE(ref.converged);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(r.mode_eigenvalues(k) / ref.eigenvalues(k), 1.0, 1e-9) << k;
}

TEST(CraigBampton, ConvergesFromAboveAsModesAreAdded) {
  const fe::Model m = test::rig_fixed_frame(4);
  const fe::AssembledSystem sys = fe::assemble(m);
  const auto b = joint_translations(m, sys, "upper_joints");
  linalg::EigenOptions eo;
  eo.count = 6;
  const auto full = linalg::solve_lanczos(sys.K, sys.M, eo);
  ASSERT_TRUE(full.converged);
  Eigen::VectorXd previous = Eigen::VectorXd::Constant(6, 1e300);
  for (int modes : {0, 2, 5, 10, 20, 40, 80, 160}) {
    const ComponentModeOptions o = modes > 0 ? craig_bampton(modes) : ComponentModeOptions{};  // 0: Guyan
    const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, b, o);
    ASSERT_TRUE(r.ok) << r.message;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(r.K, r.M);
    const Eigen::VectorXd lambda = es.eigenvalues().head(6);
    for (int k = 0; k < 6; ++k) {
      // Rayleigh-Ritz on nested subspaces: upper bounds, never rising.
      EXPECT_GE(lambda(k), full.eigenvalues(k) * (1 - 1e-9)) << modes << " modes, mode " << k + 1;
      EXPECT_LE(lambda(k), previous(k) * (1 + 1e-9)) << modes << " modes, mode " << k + 1;
    }
    previous = lambda;
    if (modes == 160) {
      // The members' local modes crowd the fixed-interface spectrum, so
      // convergence is slow (docs/reduction.md has the table: 0.09% on mode 6
      // at 40 modes, 0.006% at 80); at 160 the first six are converged.
      EXPECT_LE((lambda.array() / full.eigenvalues.array() - 1).abs().maxCoeff(), 1e-5);
    }
  }
}

TEST(CraigBampton, CutoffKeepsExactlyTheModesBelowIt) {
  const fe::Model m = test::rig_fixed_frame(3);
  const fe::AssembledSystem sys = fe::assemble(m);
  const auto b = joint_translations(m, sys, "upper_joints");
  const ReducedMatrices all = reduction::reduce_component(sys.K, sys.M, b, craig_bampton(30));
  ASSERT_TRUE(all.ok);
  // A cutoff halfway between modes 17 and 18 (30 modes: the doubling search
  // passes it from a first guess of 12).
  const double f17 = std::sqrt(all.mode_eigenvalues(16)) / (2 * M_PI);
  const double f18 = std::sqrt(all.mode_eigenvalues(17)) / (2 * M_PI);
  ASSERT_GT(f18 - f17, 1e-6 * f18);
  ComponentModeOptions by_cutoff;
  by_cutoff.method = ReductionMethod::craig_bampton;
  by_cutoff.cutoff_hz = 0.5 * (f17 + f18);
  const ReducedMatrices cut = reduction::reduce_component(sys.K, sys.M, b, by_cutoff);
  ASSERT_TRUE(cut.ok) << cut.message;
  ASSERT_EQ(cut.mode_eigenvalues.size(), 17);
  for (int k = 0; k < 17; ++k) EXPECT_NEAR(cut.mode_eigenvalues(k) / all.mode_eigenvalues(k), 1.0, 1e-9);
}

TEST(ComponentModes, FloatingInterfaceThatCannotHoldTheFrameIsAMechanism) {
  const fe::Model m = test::rig_carrying_frame();
  const fe::AssembledSystem sys = fe::assemble(m);
  auto b = joint_translations(m, sys, "lower_joints");
  b.resize(6);  // two joints: the frame can still turn about the line through them
  const ReducedMatrices r = reduction::reduce_component(sys.K, sys.M, b, {});
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.mechanism_dofs.empty());
  EXPECT_NE(r.message.find("singular"), std::string::npos) << r.message;
}

TEST(ComponentModes, RejectsInvalidInput) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(4, 4) * 2.0;
  const SpMat Ks = sparse(K), Ms = sparse(Eigen::MatrixXd::Identity(4, 4));
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {}, {}), std::invalid_argument);
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {0, 4}, {}), std::invalid_argument);
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {1, 1}, {}), std::invalid_argument);
  EXPECT_THROW(reduction::reduce_component(Ks, sparse(Eigen::MatrixXd::Identity(3, 3)), {0}, {}),
               std::invalid_argument);
  ComponentModeOptions o = craig_bampton(3);  // only 2 interior DOFs
  try {
    reduction::reduce_component(Ks, Ms, {0, 1}, o);
    ADD_FAILURE() << "expected a throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("interior has only 2"), std::string::npos) << e.what();
  }
  o.modes = 0;
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {0, 1}, o), std::invalid_argument);  // neither count nor cutoff
  o.modes = 1;
  o.cutoff_hz = 10.0;
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {0, 1}, o), std::invalid_argument);  // both
  ComponentModeOptions g;
  g.modes = 2;  // Guyan keeps no modes
  EXPECT_THROW(reduction::reduce_component(Ks, Ms, {0, 1}, g), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex
