// The rigflex command line end to end: the bundled examples, the output
// files, bad input and mechanisms.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli_support.hpp"

namespace {

using namespace rigflex::test;

TEST(Cli, ModesOfTheBeamFrameExampleWritesJsonAndParaViewFiles) {
  const fs::path out = fresh_dir("beam");
  const CliRun r = run("modes " + example("beam-frame") + " --count 6 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("mode"), std::string::npos);
  std::ifstream in(out / "modes.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["frequencies_hz"].size(), 6u);
  for (size_t k = 1; k < 6; ++k) EXPECT_GE(j["frequencies_hz"][k].get<double>(), j["frequencies_hz"][k - 1].get<double>());
  ASSERT_TRUE(j["modes"][0].contains("effective_mass_fraction"));
  double sum_tx = 0;
  for (const auto& m : j["modes"]) sum_tx += m["effective_mass_fraction"]["TX"].get<double>();
  EXPECT_GT(sum_tx, 0.0);
  EXPECT_LE(sum_tx, 1.0 + 1e-9);  // fractions of the total cannot exceed it
  // The running sum ends at the fractions' sum; effective mass = participation^2 (M-normalized shapes).
  EXPECT_NEAR(j["modes"][5]["cumulative_effective_mass_fraction"]["TX"].get<double>(), sum_tx, 1e-12);
  const double mass = j["mass_properties"]["mass"].get<double>();
  for (const auto& m : j["modes"]) {
    const double g = m["participation_factor"]["TX"].get<double>();
    EXPECT_NEAR(m["effective_mass"]["TX"].get<double>(), g * g, 1e-9 * mass);
    const double share = m["translation_share"].get<double>();
    EXPECT_TRUE(share >= 0.0 && share <= 1.0 + 1e-9) << share;
  }
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_NE(r.out.find("sum"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out / "modes.pvd"));
  for (int k = 1; k <= 6; ++k) EXPECT_TRUE(fs::exists(out / ("mode_00" + std::to_string(k) + ".vtu")));
  for (const auto& e : fs::directory_iterator(out)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
  std::ifstream vtu(out / "mode_001.vtu");
  std::stringstream ss;
  ss << vtu.rdbuf();
  EXPECT_NE(ss.str().find("UnstructuredGrid"), std::string::npos);
  EXPECT_NE(ss.str().find("frequency_hz"), std::string::npos);
  fs::remove_all(out);
}

TEST(Cli, ModesOfTheShellPlateExample) {
  const fs::path out = fresh_dir("plate");
  const CliRun r = run("modes " + example("shell-plate") + " --count 4 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / "mode_004.vtu"));
  const nlohmann::json automatic = nlohmann::json::parse(std::ifstream(out / "modes.json"));
  // --block sets the Lanczos block size; the modes agree to the solver's
  // tolerance (1e-10 on the transformed problem; 1e-9 leaves room for the
  // different Krylov spaces).
  const CliRun blocked = run("modes " + example("shell-plate") + " --count 4 --block 3 --quiet --out " + out.string());
  ASSERT_EQ(blocked.code, 0) << blocked.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "modes.json"));
  EXPECT_EQ(j["solver"]["block_size"].get<int>(), 3);
  EXPECT_EQ(automatic["solver"]["block_size"].get<int>(), 1);  // a small plate: single vector
  for (size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(j["frequencies_hz"][k].get<double>(), automatic["frequencies_hz"][k].get<double>(),
                1e-9 * automatic["frequencies_hz"][k].get<double>());
  EXPECT_NE(run("modes " + example("shell-plate") + " --block -1 --quiet").code, 0);
  fs::remove_all(out);
}

// A Lanczos run held to a basis of 14 vectors and one restart for 12
// modes stops short: without the retry the command names the cause and the
// options, exits 1 and writes nothing; with it (the default) the basis grows
// and the modes are those of the default run.
TEST(Cli, ModesThatDoNotConvergeWriteNothingOrAreRetried) {
  const fs::path out = fresh_dir("stalled");
  const std::string held = "modes " + example("shell-plate") + " --count 12 --subspace 14 --block 1 --max-restarts 1 ";
  const CliRun stalled = run(held + "--no-retry --quiet --out " + out.string());
  EXPECT_EQ(stalled.code, 1) << stalled.out;
  EXPECT_NE(stalled.out.find("not converged after 1 restarts"), std::string::npos) << stalled.out;
  EXPECT_NE(stalled.out.find("enlarge the basis (now 14) to 56"), std::string::npos) << stalled.out;
  EXPECT_NE(stalled.out.find("--subspace"), std::string::npos) << stalled.out;
  EXPECT_NE(stalled.out.find("nothing written"), std::string::npos) << stalled.out;
  EXPECT_FALSE(fs::exists(out / "modes.json"));
  EXPECT_FALSE(fs::exists(out / "mode_001.vtu"));

  const CliRun retried = run(held + "--quiet --out " + out.string());
  ASSERT_EQ(retried.code, 0) << retried.out;
  EXPECT_NE(retried.out.find("converged on an automatic retry"), std::string::npos) << retried.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "modes.json"));
  EXPECT_EQ(j["solver"]["automatic_retries"].get<int>(), 1);
  EXPECT_NE(j["solver"]["first_attempt"].get<std::string>().find("not converged"), std::string::npos);
  const fs::path reference = fresh_dir("unstalled");
  ASSERT_EQ(run("modes " + example("shell-plate") + " --count 12 --quiet --out " + reference.string()).code, 0);
  const nlohmann::json ref = nlohmann::json::parse(std::ifstream(reference / "modes.json"));
  // Both runs converge to the solver's tolerance (1e-10 on the transformed
  // problem); 1e-9 leaves room for the different Krylov spaces.
  for (size_t k = 0; k < 12; ++k)
    EXPECT_NEAR(j["frequencies_hz"][k].get<double>(), ref["frequencies_hz"][k].get<double>(),
                1e-9 * ref["frequencies_hz"][k].get<double>());
  fs::remove_all(out);
  fs::remove_all(reference);
}

TEST(Cli, MassPrintsTheSpecRecord) {
  const CliRun r = run("mass --json " + example("shell-plate"));
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // 2 x 1 x 0.012 m of steel plus the 40 kg block.
  EXPECT_NEAR(j["mass"].get<double>(), 2.0 * 1.0 * 0.012 * 7850 + 40.0, 1e-9);
  EXPECT_EQ(j["inertia"].size(), 6u);
}

// The solids example: beam, solid block, rigid and distributing couplings.
TEST(Cli, BearingBlockExampleHasItsMassAndSolidModes) {
  const CliRun mass = run("mass --json " + example("bearing-block"));
  ASSERT_EQ(mass.code, 0) << mass.out;
  // Box beam 3 m x (0.2 x 0.3 - 0.18 x 0.28) m^2 of steel, a 0.3 x 0.3 x 0.4 m
  // cast-iron block, the 250 kg rotor (through the distributing coupling).
  const double expected = 3.0 * (0.2 * 0.3 - 0.18 * 0.28) * 7850 + 0.3 * 0.3 * 0.4 * 7200 + 250.0;
  EXPECT_NEAR(nlohmann::json::parse(mass.out)["mass"].get<double>(), expected, 1e-9 * expected);

  const fs::path out = fresh_dir("bearing");
  const CliRun r = run("modes " + example("bearing-block") + " --count 4 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "modes.json"));
  ASSERT_EQ(j["frequencies_hz"].size(), 4u);
  EXPECT_GT(j["frequencies_hz"][0].get<double>(), 1.0);  // supported: no rigid-body mode
  // The mode files carry every element: 12 beams, 36 hex20, 1 point mass.
  std::stringstream vtu;
  vtu << std::ifstream(out / "mode_001.vtu").rdbuf();
  EXPECT_NE(vtu.str().find("NumberOfCells=\"49\""), std::string::npos);
  fs::remove_all(out);
}

TEST(Cli, BadInputNamesFileLineAndKeyAndWritesNothing) {
  const fs::path model = write_model("bad", "materials:\n  steel: {E: 2.1e11, nu: 0.3, rho: 7850, colour: 1}\n");
  const fs::path out = fresh_dir("bad");
  const CliRun r = run("modes " + model.string() + " --out " + out.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find(model.string() + ":2: key 'colour'"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
  fs::remove(model);
}

TEST(Cli, MechanismIsReportedWithItsFreeDofs) {
  // A massless member that nothing holds: its rigid motions have neither
  // stiffness nor mass, so K - sigma M is singular for every shift.
  const fs::path model = write_model("mech", R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  b: {material: steel, shape: circle, diameter: 0.05}
nodes:
  - [1, 0, 0, 0]
  - [2, 1, 0, 0]
  - [3, 0, 1, 0]
  - [4, 1, 1, 0]
beams:
  - {id: held, nodes: [1, 2], section: b}
  - {id: loose, nodes: [3, 4], section: b, mass: none}
supports:
  - {node: 1, dofs: all}
)");
  const fs::path out = fresh_dir("mech");
  const CliRun r = run("modes " + model.string() + " --count 2 --quiet --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("mechanism"), std::string::npos) << r.out;
  for (const char* dof : {"node 3 UY", "node 4 UZ"}) EXPECT_NE(r.out.find(dof), std::string::npos) << dof << "\n" << r.out;
  EXPECT_EQ(r.out.find("node 2 "), std::string::npos) << r.out;  // the held member is not part of it
  EXPECT_FALSE(fs::exists(out));
  fs::remove(model);
}

}  // namespace
