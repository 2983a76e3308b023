// The MPI eigen backend (linalg/slepc_eigen.hpp) against the built-in
// Lanczos on the same K and M. Run by ctest under mpiexec at 1, 2 and 4
// ranks: every rank runs every test (the solves are collective); all ranks
// assert, rank 0 prints.
//
// Tolerance: both solvers converge each pair to a relative residual of
// 1e-10 on well-separated spectra, so their eigenvalues agree to ~1e-10
// relative; 1e-8 (the bar) leaves two orders for rounding across
// different factorizations (MUMPS vs CHOLMOD, different orderings).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Eigen/Eigenvalues>
#include <cstdio>

#include "fe/assembly.hpp"
#include "io/model_reader.hpp"
#include "linalg/slepc_eigen.hpp"
#include "reduction/frame_reduction.hpp"
#include "support/frame_models.hpp"

namespace {

using namespace rigflex;
using linalg::EigenResult;
using linalg::SlepcOptions;
using linalg::SpMat;

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int ranks() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

// A cantilever plate, 1.2 x 0.7 m, 8 mm, 24 x 14 MITC4 shells (2100 DOFs):
// a spectrum with bending and torsion modes, no two equal.
fe::AssembledSystem plate() {
  fe::Model m = test::steel_model();
  test::clamped_plate(m, 1.2, 0.7, 0.008, 24, 14, false);
  return fe::assemble(m);
}

linalg::EigenResult builtin(const SpMat& K, const SpMat& M, int count) {
  linalg::EigenOptions o;
  o.count = count;
  o.method = linalg::EigenMethod::lanczos;
  return linalg::solve_lanczos(K, M, o);
}

// Each of SLEPc's vectors lies in the built-in solver's eigenspace of its
// eigenvalue (the space of the built-in vectors whose eigenvalues lie within
// `cluster` relative of it): the M-norm of its projection there is 1.
void expect_same_eigenspaces(const SpMat& M, const EigenResult& mine, const EigenResult& reference, double cluster) {
  const double top = reference.eigenvalues.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < mine.vectors.cols(); ++i) {
    std::vector<Eigen::Index> space;
    for (Eigen::Index j = 0; j < reference.eigenvalues.size(); ++j)
      if (std::abs(reference.eigenvalues[j] - mine.eigenvalues[i]) <= cluster * top) space.push_back(j);
    ASSERT_FALSE(space.empty()) << "pair " << i;
    const Eigen::VectorXd Mx = M * mine.vectors.col(i);
    double projected = 0;
    for (Eigen::Index j : space) projected += std::pow(reference.vectors.col(j).dot(Mx), 2);
    EXPECT_NEAR(projected, 1.0, 1e-8) << "pair " << i << " of " << mine.vectors.cols();
  }
}

void expect_checked(const EigenResult& r, int count) {
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.eigenvalues.size(), count);
  ASSERT_EQ(r.vectors.cols(), count);
  // The contract every eigen solver of rigflex meets (docs/eigen-solver.md,
  // "Every pair is checked"): the solver's tolerance.
  EXPECT_LE(r.orthogonality_error, 1e-10);
  EXPECT_LE(r.backward_errors.maxCoeff(), 1e-10);
}

// The built-in Lanczos' and SLEPc's lowest `count` pairs of sys, the
// vectors on every rank.
struct BothSolvers {
  EigenResult reference, slepc;
};
BothSolvers solve_both(const fe::AssembledSystem& sys, int count) {
  BothSolvers b;
  b.reference = builtin(sys.K, sys.M, count);
  SlepcOptions o;
  o.count = count;
  o.gather = linalg::SlepcGather::all;
  b.slepc = linalg::solve_slepc(sys.K, sys.M, o);
  return b;
}

TEST(SlepcEigen, PlateModesEqualTheBuiltInLanczos) {
  const fe::AssembledSystem sys = plate();
  const int count = 12;
  const auto [reference, r] = solve_both(sys, count);
  ASSERT_TRUE(reference.converged) << reference.message;
  expect_checked(r, count);
  EXPECT_LE(r.residuals.maxCoeff(), 1e-8);
  for (int i = 0; i < count; ++i)
    EXPECT_NEAR(r.eigenvalues[i] / reference.eigenvalues[i], 1.0, 1e-8) << "mode " << i + 1 << " on " << ranks();
  expect_same_eigenspaces(sys.M, r, reference, 1e-8);
}

TEST(SlepcEigen, VectorsGatheredOnRankZeroOnly) {
  const fe::AssembledSystem sys = plate();
  SlepcOptions o;
  o.count = 6;
  const EigenResult r = linalg::solve_slepc(sys.K, sys.M, o);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.eigenvalues.size(), 6);  // the values on every rank
  if (rank() == 0) {
    expect_checked(r, 6);
  } else {
    EXPECT_EQ(r.vectors.cols(), 0);
  }
  // The same values on every rank, to the bit.
  Eigen::VectorXd root = r.eigenvalues;
  MPI_Bcast(root.data(), 6, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  EXPECT_EQ(root, r.eigenvalues);
}

// A floating frame: six rigid-body modes at lambda = 0 (singular K; the
// shift below zero makes K - sigma M definite) and a singular M would do
// the same for massless rotations.
TEST(SlepcEigen, FloatingFrameRigidBodyAndElasticModes) {
  const fe::AssembledSystem sys = fe::assemble(test::rig_carrying_frame(4));
  const int count = 14;
  const auto [reference, r] = solve_both(sys, count);
  ASSERT_TRUE(reference.converged) << reference.message;
  expect_checked(r, count);
  const double first_elastic = reference.eigenvalues[6];
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(r.eigenvalues[i]), 1e-8 * first_elastic) << "rigid mode " << i + 1;
  for (int i = 6; i < count; ++i)
    EXPECT_NEAR(r.eigenvalues[i] / reference.eigenvalues[i], 1.0, 1e-8) << "mode " << i + 1;
  // The rigid-body modes as a space: each SLEPc rigid vector within the
  // built-in six (a cluster at 0 of width 1e-8 of the top eigenvalue).
  expect_same_eigenspaces(sys.M, r, reference, 1e-8);
}

TEST(SlepcEigen, EveryDirectSolverGivesTheSameModes) {
  const fe::AssembledSystem sys = plate();
  SlepcOptions o;
  o.count = 8;
  o.gather = linalg::SlepcGather::all;
  if (ranks() > 1) {
    // CHOLMOD and PETSc's Cholesky are sequential: refused, naming mumps.
    for (auto s : {linalg::SlepcDirectSolver::cholmod, linalg::SlepcDirectSolver::petsc}) {
      o.direct_solver = s;
      try {
        linalg::solve_slepc(sys.K, sys.M, o);
        ADD_FAILURE() << "a sequential solver accepted on " << ranks() << " ranks";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("use mumps"), std::string::npos) << e.what();
      }
    }
    return;
  }
  const EigenResult mumps = linalg::solve_slepc(sys.K, sys.M, o);
  expect_checked(mumps, 8);
  for (auto s : {linalg::SlepcDirectSolver::cholmod, linalg::SlepcDirectSolver::petsc}) {
    o.direct_solver = s;
    const EigenResult r = linalg::solve_slepc(sys.K, sys.M, o);
    expect_checked(r, 8);
    for (int i = 0; i < 8; ++i)
      EXPECT_NEAR(r.eigenvalues[i] / mumps.eigenvalues[i], 1.0, 1e-8) << to_string(s) << " mode " << i + 1;
  }
}

// Craig-Bampton with the backend for its eigenproblems (the full model's
// modes and the fixed-interface modes): the reduced pencil has the same
// spectrum as with the built-in Lanczos, to 1e-8.
TEST(SlepcEigen, CraigBamptonReductionEqualsTheBuiltIn) {
  const fe::Model frame = test::rig_carrying_frame(4);
  reduction::FrameReductionOptions o;
  o.interface_set = "lower_joints";
  o.method = reduction::ReductionMethod::craig_bampton;
  o.modes = 10;
  const reduction::ReducedFrame reference = reduction::reduce_frame(frame, o);
  SlepcOptions base;
  base.gather = linalg::SlepcGather::all;
  o.eigen_backend = linalg::slepc_backend(base);
  const reduction::ReducedFrame r = reduction::reduce_frame(frame, o);
  ASSERT_EQ(r.mode_frequencies_hz.size(), 10);
  for (int i = 0; i < 10; ++i)
    EXPECT_NEAR(r.mode_frequencies_hz[i] / reference.mode_frequencies_hz[i], 1.0, 1e-8) << "fixed-interface mode " << i;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> mine(r.K, r.M), theirs(reference.K, reference.M);
  const Eigen::VectorXd a = mine.eigenvalues(), b = theirs.eigenvalues();
  const double top = b.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-8 * std::max(std::abs(b[i]), 1e-6 * top)) << i;
  EXPECT_EQ(r.checks.rigid_body_modes_full, 6);
  EXPECT_EQ(r.checks.rigid_body_modes_reduced, 6);
}

TEST(SlepcEigen, InvalidOptionsAreRefused) {
  const fe::AssembledSystem sys = plate();
  SlepcOptions o;
  o.count = static_cast<int>(sys.K.rows()) + 1;
  EXPECT_THROW(linalg::solve_slepc(sys.K, sys.M, o), std::invalid_argument);
  o.count = 4;
  o.tolerance = 0;
  EXPECT_THROW(linalg::solve_slepc(sys.K, sys.M, o), std::invalid_argument);
  o.tolerance = 1e-10;
  o.subspace = 3;  // not above count
  EXPECT_THROW(linalg::solve_slepc(sys.K, sys.M, o), std::invalid_argument);
  EXPECT_THROW(linalg::parse_slepc_direct_solver("superlu"), std::invalid_argument);
  const SpMat small = sys.K.topLeftCorner(10, 10);
  o.subspace = 0;
  EXPECT_THROW(linalg::solve_slepc(small, sys.M, o), std::invalid_argument);
}

// The other ranks print their failures only, marked with the rank.
class FailuresOfRank : public ::testing::EmptyTestEventListener {
 public:
  explicit FailuresOfRank(int rank) : rank_(rank) {}
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (r.failed())
      std::fprintf(stderr, "[rank %d] %s:%d: failure\n%s\n", rank_, r.file_name() ? r.file_name() : "?",
                   r.line_number(), r.summary());
  }

 private:
  int rank_;
};

}  // namespace

// PETSc and MPI for the whole program; gtest's report from rank 0 (every
// rank runs and asserts, and mpiexec fails if any rank fails).
int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const rigflex::linalg::SlepcSession session;
  if (session.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new FailuresOfRank(session.rank()));
  }
  return RUN_ALL_TESTS();
}
