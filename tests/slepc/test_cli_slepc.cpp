// `rigflex modes` and `rigflex reduce` with --backend slepc under mpiexec:
// the same results as the built-in Lanczos (to 1e-8 relative: see
// test_slepc_eigen.cpp), rank 0 alone printing and writing, a sequential
// direct solver refused on two ranks.
#include <gtest/gtest.h>

#include <string>

#include "apps/cli_support.hpp"
#include "io/reduced_export.hpp"

namespace {

using namespace rigflex::test;

// mpiexec as root and with more ranks than cores (the test machines).
CliRun mpi(int ranks, const std::string& args) {
  return run_command("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 " +
                     std::string(RIGFLEX_MPIEXEC) + " -n " + std::to_string(ranks) + " " + RIGFLEX_CLI + " " + args +
                     " 2>&1");
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(CliSlepc, ModesOnTwoRanksEqualTheBuiltIn) {
  const fs::path builtin = fresh_dir("slepc_modes_builtin"), slepc = fresh_dir("slepc_modes_mpi");
  const CliRun a = run("modes " + example("beam-frame") + " --count 8 --quiet --out " + builtin.string());
  ASSERT_EQ(a.code, 0) << a.out;
  const CliRun b = mpi(2, "modes " + example("beam-frame") + " --count 8 --backend slepc --out " + slepc.string());
  ASSERT_EQ(b.code, 0) << b.out;
  EXPECT_EQ(count_of(b.out, "model: "), 1u) << "rank 0 alone prints:\n" << b.out;
  EXPECT_NE(b.out.find("SLEPc Krylov-Schur, shift-invert, MUMPS on 2 MPI ranks"), std::string::npos) << b.out;
  const auto x = read_json(builtin / "modes.json"), y = read_json(slepc / "modes.json");
  ASSERT_EQ(y["modes"].size(), 8u);
  for (size_t i = 0; i < 8; ++i) {
    const double f = x["modes"][i]["frequency_hz"], g = y["modes"][i]["frequency_hz"];
    EXPECT_NEAR(g / f, 1.0, 1e-8) << "mode " << i + 1;
    EXPECT_LE(static_cast<double>(y["modes"][i]["residual"]), 1e-8);
  }
  EXPECT_NE(y["solver"]["method"].get<std::string>().find("SLEPc"), std::string::npos);
  EXPECT_LE(static_cast<double>(y["solver"]["orthogonality_error"]), 1e-10);
  EXPECT_TRUE(fs::exists(slepc / "mode_008.vtu"));
  fs::remove_all(builtin);
  fs::remove_all(slepc);
}

TEST(CliSlepc, CraigBamptonOnTwoRanksEqualsTheBuiltIn) {
  const fs::path builtin = fresh_dir("slepc_reduce_builtin"), slepc = fresh_dir("slepc_reduce_mpi");
  const std::string args = "reduce " + example("carrying-frame") +
                           " --interface lower_joints --method craig-bampton "
                           "--modes 12 --quiet --out ";
  const CliRun a = run(args + builtin.string());
  ASSERT_EQ(a.code, 0) << a.out;
  const CliRun b = mpi(2, args + slepc.string() + " --backend slepc");
  ASSERT_EQ(b.code, 0) << b.out;
  EXPECT_EQ(count_of(b.out, "wrote "), 1u) << b.out;
  const auto x = rigflex::io::read_reduced_frame(builtin), y = rigflex::io::read_reduced_frame(slepc);
  ASSERT_EQ(y.mode_frequencies_hz.size(), 12);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(y.mode_frequencies_hz[i] / x.mode_frequencies_hz[i], 1.0, 1e-8) << i;
  EXPECT_EQ(y.checks.rigid_body_modes_reduced, x.checks.rigid_body_modes_reduced);
  EXPECT_NEAR(y.damping.alpha / x.damping.alpha, 1.0, 1e-8);  // from the full model's modes 1 and 3
  EXPECT_NEAR(y.damping.beta / x.damping.beta, 1.0, 1e-8);
  fs::remove_all(builtin);
  fs::remove_all(slepc);
}

TEST(CliSlepc, ASequentialDirectSolverOnTwoRanksIsRefused) {
  const fs::path out = fresh_dir("slepc_cholmod_two");
  const CliRun r =
      mpi(2, "modes " + example("beam-frame") + " --backend slepc --direct-solver cholmod --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("cholmod runs on one rank only"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "modes.json"));
}

}  // namespace
