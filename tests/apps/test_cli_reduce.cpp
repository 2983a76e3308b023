// `rigflex reduce` end to end on the bundled fixed and carrying frames: the
// checks it prints, the files it writes (read back), and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/cli_support.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_export.hpp"
#include "io/reduced_mat.hpp"

namespace {

using namespace rigflex::test;
namespace reduction = rigflex::reduction;

void expect_no_temporaries(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
}

TEST(CliReduce, FixedFrameExampleGuyanGrounded) {
  const fs::path out = fresh_dir("reduce_fixed");
  const CliRun r = run("reduce " + example("beam-frame") + " --interface upper_joints --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("guyan, grounded"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("static interface flexibility"), std::string::npos);
  for (const char* f : {"reduced.json", "reduced.mat", "K.mtx", "M.mtx", "C.mtx", "ss_A.mtx", "ss_B.mtx", "ss_C.mtx",
                        "ss_D.mtx", "ss_T.mtx"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  expect_no_temporaries(out);
  const reduction::ReducedFrame f = rigflex::io::read_reduced_frame(out);
  EXPECT_EQ(f.method, reduction::ReductionMethod::guyan);
  EXPECT_EQ(f.support, reduction::FrameSupport::grounded);
  ASSERT_EQ(f.K.rows(), 18);  // three joints, six DOFs each (the default, what Simscape takes)
  EXPECT_EQ(f.retained, reduction::InterfaceDofs::all);
  EXPECT_EQ(f.state_space.coordinates, reduction::StateCoordinates::physical);  // a held frame
  EXPECT_LE(f.checks.static_flexibility_error, 1e-10);
  EXPECT_EQ(f.checks.rigid_body_modes_reduced, 0);
  // Rayleigh: 2 % at elastic modes 1 and 3 of the full model by default.
  EXPECT_EQ(f.damping.modes[0], 1);
  EXPECT_EQ(f.damping.modes[1], 3);
  const double w1 = f.damping.omega[0], w3 = f.damping.omega[1];
  EXPECT_NEAR(f.damping.alpha / (2 * w1) + f.damping.beta * w1 / 2, 0.02, 1e-15);
  EXPECT_NEAR(f.damping.alpha / (2 * w3) + f.damping.beta * w3 / 2, 0.02, 1e-15);
  // The .mat file holds the same matrices, bit for bit.
  const auto mat = rigflex::io::read_reduced_mat(out / "reduced.mat");
  EXPECT_EQ(mat.K, f.K);
  EXPECT_EQ(mat.M, f.M);
  EXPECT_EQ(mat.C, f.C);
  fs::remove_all(out);
}

TEST(CliReduce, CarryingFrameExampleCraigBamptonFreeFree) {
  const fs::path out = fresh_dir("reduce_carrying");
  const CliRun r = run("reduce " + example("carrying-frame") +
                       " --interface lower_joints --method craig-bampton --modes 12 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("craig-bampton, free"), std::string::npos) << r.out;
  const reduction::ReducedFrame f = rigflex::io::read_reduced_frame(out);
  ASSERT_EQ(f.K.rows(), 18 + 12);
  EXPECT_EQ(f.mode_count, 12);
  EXPECT_EQ(f.checks.rigid_body_modes_full, 6);
  EXPECT_EQ(f.checks.rigid_body_modes_reduced, 6);
  EXPECT_TRUE(f.checks.mass_comparable);
  EXPECT_NEAR(f.checks.mass_reduced.mass / f.checks.mass_full.mass, 1.0, 1e-12);
  EXPECT_LE(f.checks.static_flexibility_error, 1e-10);
  // The state-space matrices have the documented sizes: x = [xi; xi'], u at the interface;
  // a free frame's state is modal, its six rigid-body modes exact.
  EXPECT_EQ(f.state_space.A.rows(), 60);
  EXPECT_EQ(f.state_space.B.cols(), 18);
  EXPECT_EQ(f.state_space.C.rows(), 36);
  EXPECT_EQ(f.state_space.coordinates, reduction::StateCoordinates::modal);
  EXPECT_EQ(f.state_space.rigid_body_modes, 6);
  EXPECT_NE(r.out.find("modal coordinates (z = T xi), the 6 rigid-body modes exact"), std::string::npos) << r.out;
  fs::remove_all(out);
}

// reduced.mat as Simscape's Reduced Order Flexible Solid takes it, read by
// SciPy (independent of the matio that wrote it): six DOFs per interface
// frame in the block's order by default, symmetric matrices, a positive
// definite mass, and the free frame's state space with exactly 12 zero
// eigenvalues (its six rigid-body modes) where the physical form has none.
TEST(CliReduce, MatFileRebuildsTheSimscapeBlockInputsInScipy) {
  const fs::path out = fresh_dir("reduce_simscape");
  const CliRun r = run("reduce " + example("carrying-frame") +
                       " --interface lower_joints --method craig-bampton --modes 12 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string script = std::string(RIGFLEX_SOURCE_DIR) + "/tests/apps/simscape_inputs.py";
  // Debian's interpreter, which has python3-scipy (a python3 first on PATH may not).
  const std::string cmd = "/usr/bin/python3 " + script + " " + (out / "reduced.mat").string() + " 2>&1";
  const CliRun py = run_command(cmd);
  ASSERT_EQ(py.code, 0) << py.out;
  const std::string& text = py.out;
  const auto j = nlohmann::json::parse(text);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["modes"], 12);
  EXPECT_EQ(j["coordinates"], 6 * 3 + 12);
  EXPECT_TRUE(j["six_dofs_per_frame"].get<bool>()) << text;
  EXPECT_TRUE(j["origins_finite"].get<bool>());
  // rigflex symmetrizes K, M and C; what is left is the last bit.
  EXPECT_LE(j["symmetry_error"].get<double>(), 1e-15) << text;
  EXPECT_TRUE(j["mass_positive_definite"].get<bool>());
  EXPECT_EQ(j["A_zero_eigenvalues"], 12) << text;
  // Damped elastic modes: every other pole strictly in the left half-plane.
  EXPECT_LT(j["A_largest_real_part_of_the_others"].get<double>(), 0.0) << text;
  EXPECT_EQ(j["T_shape"], (nlohmann::json{30, 30}));
  // The reason for the modal form: in x = [z; z'] the rigid motions carry K's
  // round-off and none of their 12 eigenvalues is zero.
  EXPECT_GT(j["physical_A_largest_of_12_smallest_eigenvalues"].get<double>(), 0.0) << text;
  fs::remove_all(out);
}

TEST(CliReduce, BadOptionsAreNamedAndWriteNothing) {
  const fs::path out = fresh_dir("reduce_bad");
  const std::string fixed = example("beam-frame");
  struct Case {
    std::string args, fragment;
  };
  const std::vector<Case> cases{
      {fixed + " --interface nope", "'nope' does not exist"},
      {fixed + " --interface upper_joints --zeta 1.5", "zeta"},
      {fixed + " --interface upper_joints --zeta-modes 2,2", "zeta modes"},
      {fixed + " --interface upper_joints --zeta-modes 1,100000", "does not exist"},
      {fixed + " --interface upper_joints --modes 3", "Guyan"},
      {fixed + " --interface upper_joints --method craig-bampton --modes 100000", "interior has only"},
      {fixed + " --interface upper_joints --support free", "floating"},
      {example("carrying-frame") + " --interface lower_joints --support grounded", "needs supports"},
  };
  for (const auto& c : cases) {
    const CliRun r = run("reduce " + c.args + " --quiet --out " + out.string());
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.fragment), std::string::npos) << c.args << "\n" << r.out;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

TEST(CliReduce, InterfaceThatCannotHoldAFloatingFrameNamesTheFreeDofs) {
  // Two joints, translations only: the frame can turn about the line through them.
  std::ifstream in(example("carrying-frame"));
  std::stringstream text;
  text << in.rdbuf() << "node_sets:\n  two: {box: [[-2.0, -1.2, 0.11], [2.0, -1.0, 0.13]]}\n";
  const fs::path model = write_model("two_joints", text.str());
  const fs::path out = fresh_dir("reduce_mech");
  const CliRun r =
      run("reduce " + model.string() + " --interface two --dofs translations --quiet --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("free DOFs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("node "), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
  fs::remove(model);
}

}  // namespace

namespace {

using namespace rigflex::test;

// `rigflex export`: a model's deck, a reduced frame's DMIG and Abaqus
// matrices, and the usage errors (exit 2, nothing written).
TEST(CliExport, DeckDmigAndAbaqusMatricesOfTheCarryingFrame) {
  const fs::path out = fresh_dir("export_carrying");
  CliRun r = run("export " + example("carrying-frame") + " --deck " + (out / "frame.inp").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream deck(out / "frame.inp");
  const std::string text((std::istreambuf_iterator<char>(deck)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("*STEP\n*FREQUENCY\n10\n"), std::string::npos);
  EXPECT_NE(text.find("*EQUATION"), std::string::npos);  // the frame's rigid couplings
  r = run("reduce " + example("carrying-frame") +
          " --interface lower_joints --method craig-bampton --modes 4 --quiet "
          "--node-dofs " +
          std::to_string(rigflex::io::read_model(example("carrying-frame")).model.node_set("lower_joints")[0]) +
          ":UX,UZ --out " + (out / "red").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(rigflex::io::read_reduced_frame(out / "red").interface_dofs.size(), 14u);  // 2 + 6 + 6
  r = run("export --reduced " + (out / "red").string() + " --dmig " + (out / "frame.dmig").string() +
          " --abaqus-matrix " + (out / "frame_abq.inp").string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* f : {"frame.dmig", "frame_abq.inp", "frame_abq_K.txt", "frame_abq_M.txt", "frame_abq_C.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  for (const std::string& bad :
       {"export --reduced " + (out / "red").string(), "export " + example("carrying-frame"),
        "export --reduced " + (out / "red").string() + " --abaqus-matrix " + (out / "x.txt").string(),
        "reduce " + example("carrying-frame") + " --interface lower_joints --node-dofs 1:UQ --out " +
            (out / "bad").string()}) {
    r = run(bad);
    EXPECT_EQ(r.code, 2) << bad << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(out / "x.txt"));
  EXPECT_FALSE(fs::exists(out / "bad"));
  fs::remove_all(out);
}

}  // namespace
