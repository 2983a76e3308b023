// `rigflex compare` and `rigflex diagnose` end to end on a small trifilar:
// the files they write, the study folder, and bad input named by file,
// line and key or column.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_support.hpp"
#include "apps/cli_trifilar.hpp"

namespace {

using namespace rigflex::test;

const std::string kCompareRig = cli_trifilar_rig("cli-trifilar");

class CliCompare : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_dir("compare"));
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "rig.yaml") << kCompareRig;
    // The measured rig has a rod 3 mm too long.
    std::ofstream(*dir_ / "truth.yaml") << kCompareRig << "effects:\n  rod_length_error: {delta: [0.003, 0.0, 0.0]}\n";
    const CliRun r = run("simulate " + (*dir_ / "truth.yaml").string() + " --histories 3 --duration 8 --seed 4 --out " +
                         (*dir_ / "data").string() + " --quiet");
    ASSERT_EQ(r.code, 0) << r.out;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
  fs::path rig() const { return *dir_ / "rig.yaml"; }
  std::string data() const { return (*dir_ / "data" / "set1").string(); }
};
fs::path* CliCompare::dir_ = nullptr;

TEST_F(CliCompare, WritesTheComparisonTheReportAndTheStudy) {
  const fs::path out = *dir_ / "cmp";
  const CliRun r = run("compare " + rig().string() + " " + data() + " --study " + (*dir_ / "study").string() +
                       " --out " + out.string() + " --quiet");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = read_json(out / "compare.json");
  EXPECT_GT(j["overall_nrmse"].get<double>(), 0.0);
  for (const char* ch : {"F1", "F2", "F3", "alpha1", "beta3"}) EXPECT_TRUE(j["nrmse"].contains(ch)) << ch;
  EXPECT_EQ(j["histories"].size(), 3u);
  EXPECT_TRUE(fs::exists(out / "compare.html"));
  EXPECT_TRUE(fs::exists(out / "model" / "set1_h1.csv"));
  EXPECT_NE(r.out.find("<- this run"), std::string::npos);
  // The same version again updates its entry; the effect added is a new version.
  ASSERT_EQ(run("compare " + rig().string() + " " + data() + " --study " + (*dir_ / "study").string() + " --out " +
                out.string() + " --quiet").code, 0);
  std::ofstream(*dir_ / "fix.yaml") << "effects:\n  rod_length_error: {delta: [0.003, 0.0, 0.0]}\n";
  const CliRun fixed = run("compare " + rig().string() + " " + data() + " --effects " + (*dir_ / "fix.yaml").string() +
                           " --study " + (*dir_ / "study").string() + " --out " + (*dir_ / "cmp2").string() + " --quiet");
  ASSERT_EQ(fixed.code, 0) << fixed.out;
  const auto study = read_json(*dir_ / "study" / "study.json");
  ASSERT_EQ(study["versions"].size(), 2u);
  EXPECT_EQ(study["versions"][1]["label"], "rig.yaml + fix.yaml");
  EXPECT_LT(study["versions"][1]["force_nrmse"].get<double>(), 0.2 * study["versions"][0]["force_nrmse"].get<double>());
}

TEST_F(CliCompare, DiagnoseNamesTheEffectAndWritesItsFile) {
  const fs::path out = *dir_ / "diag";
  const CliRun r = run("diagnose " + rig().string() + " " + data() +
                       " --only rod_length_error,air_drag,load_cell_gain --out " + out.string() + " --quiet");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = read_json(out / "diagnosis.json");
  EXPECT_EQ(j["missing_effect"], "rod_length_error");
  EXPECT_EQ(j["ranking"].size(), 3u);
  EXPECT_EQ(j["ranking"][0]["effect"], "rod_length_error");
  EXPECT_TRUE(j["ranking"][0]["parameters"].contains("delta1"));
  EXPECT_TRUE(fs::exists(out / "effects" / "rod_length_error.yaml"));
  EXPECT_TRUE(fs::exists(out / "diagnosis.html"));
  // The length error brings the model to the noise: a chain of one, its
  // file the found effects' (as its own, with the chain's comment).
  ASSERT_EQ(j["chain"].size(), 1u);
  EXPECT_EQ(j["chain"][0]["rig_block"], j["ranking"][0]["rig_block"]);
  EXPECT_TRUE(j["tested_after_chain"].empty());
  EXPECT_TRUE(fs::exists(out / "effects" / "found.yaml"));
  // The written effect file is a valid --effects file, with its values'
  // uncertainty (the fit's standard deviations), which compare then
  // refits with the body: the model as found is within them.
  const std::string block = j["chain"][0]["rig_block"];
  EXPECT_NE(block.find("uncertainty:"), std::string::npos) << block;
  const CliRun again =
      run("compare " + rig().string() + " " + data() + " --effects " +
          (out / "effects" / "rod_length_error.yaml").string() + " --out " + (*dir_ / "cmp3").string() + " --quiet");
  EXPECT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("body and effects' values refitted"), std::string::npos) << again.out;
  EXPECT_EQ(again.out.find("model parameter off"), std::string::npos) << again.out;
  const auto c = read_json(*dir_ / "cmp3" / "compare.json");
  EXPECT_TRUE(c["model_fit"]["parameters"].contains("effects.rod_length_error.delta[0]")) << c["model_fit"];
}

// Two records of 8 s simulated from kCompareRig + `truth` into dir/data,
// and kCompareRig + `rig` written as dir/rig.yaml.
CliRun simulate_records(const fs::path& dir, const std::string& truth, const std::string& rig) {
  fs::create_directories(dir);
  std::ofstream(dir / "truth.yaml") << kCompareRig << truth;
  std::ofstream(dir / "rig.yaml") << kCompareRig << rig;
  return run("simulate " + (dir / "truth.yaml").string() + " --histories 2 --duration 8 --seed 4 --out " +
             (dir / "data").string() + " --quiet");
}

// simulate_records, then diagnose of dir/rig.yaml on them, the candidates
// limited to `only`, into dir/diag.
CliRun simulate_and_diagnose(const fs::path& dir, const std::string& truth, const std::string& rig,
                             const std::string& only) {
  const CliRun sim = simulate_records(dir, truth, rig);
  if (sim.code != 0) return sim;
  return run("diagnose " + (dir / "rig.yaml").string() + " " + (dir / "data" / "set1").string() + " --only " + only +
             " --out " + (dir / "diag").string() + " --quiet");
}

// compare refits the body and what the rig file states an uncertainty for
// (here the rods' stiffness, stated to 10 %, while the rods measured are
// twice as compliant): the stiffness reported off on the terminal and in
// compare.json, the comparison made with the refitted model (its force
// NRMSE below the rig file's model's, kept beside it), the report's
// section; --hold-body compares the rig file's model as it is.
TEST(CliCompareRefit, ReportsAModelParameterOff) {
  const fs::path dir = fresh_dir("compare_refit");
  ASSERT_EQ(
      simulate_records(dir, "rods: {stiffness: 2.5e5}\n", "rods: {stiffness: 5.0e5, uncertainty: {stiffness: 0.1}}\n")
          .code,
      0);
  const std::string args = (dir / "rig.yaml").string() + " " + (dir / "data" / "set1").string();
  const CliRun r = run("compare " + args + " --out " + (dir / "c").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("body and rods' stiffness refitted"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model parameter off: rods.stiffness"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("compare: fitting the body's mass properties"), std::string::npos) << r.out;
  const auto j = read_json(dir / "c" / "compare.json");
  const auto& f = j["model_fit"];
  EXPECT_EQ(f["credible"], true) << f;
  EXPECT_EQ(f["model_parameters_off"], nlohmann::json::array({"rods.stiffness"}));
  EXPECT_NEAR(f["parameters"]["rods.stiffness"]["offset"].get<double>(), -50.0, 1.0) << f;
  EXPECT_LT(j["force_nrmse"].get<double>(), 0.5 * f["as_stated"]["force_nrmse"].get<double>()) << f;
  std::ifstream html(dir / "c" / "compare.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("own parameters refitted"), std::string::npos);
  const CliRun held = run("compare " + args + " --hold-body --quiet --out " + (dir / "h").string());
  ASSERT_EQ(held.code, 0) << held.out;
  const auto jh = read_json(dir / "h" / "compare.json");
  EXPECT_FALSE(jh.contains("model_fit"));
  EXPECT_EQ(jh["force_nrmse"], f["as_stated"]["force_nrmse"]);
  fs::remove_all(dir);
}

// The rig file states the rods' stiffness and how well it is known; the
// rods measured are twice as compliant: diagnose names no missing effect,
// reports the stiffness off, prints it with the body, and writes it to
// diagnosis.json.
TEST(CliDiagnose, ReportsTheRodsStiffnessOff) {
  const fs::path dir = fresh_dir("rods_off");
  const CliRun r = simulate_and_diagnose(dir, "rods: {stiffness: 2.5e5}\n",
                                         "rods: {stiffness: 5.0e5, uncertainty: {stiffness: 0.1}}\n", "rod_compliance");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("model parameter off: rods.stiffness"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("body and rods' stiffness fitted"), std::string::npos) << r.out;
  const auto j = read_json(dir / "diag" / "diagnosis.json");
  EXPECT_TRUE(j["missing_effect"].is_null()) << j["summary"];
  EXPECT_EQ(j["model_parameters_off"], nlohmann::json::array({"rods.stiffness"}));
  EXPECT_EQ(j["body"]["rods.stiffness"]["unit"], "%");
  EXPECT_NEAR(j["body"]["rods.stiffness"]["offset"].get<double>(), -50.0, 1.0);
  // Refitted, the model reaches the noise: no candidate is fitted, and the
  // terminal and the JSON say why; --rank-all fits it anyway.
  EXPECT_TRUE(j["ranking"].empty()) << j["ranking"];
  EXPECT_NE(r.out.find("no candidate was fitted"), std::string::npos) << r.out;
  EXPECT_NE(j["ranking_note"].get<std::string>().find("reaches the noise"), std::string::npos);
  // The gate: 1 + the larger of 3 and what the default period tolerance leaves here.
  const double allowance = j["baseline"]["numerics_allowance"].get<double>();
  EXPECT_GT(allowance, 0.0);
  EXPECT_DOUBLE_EQ(j["baseline"]["gate"].get<double>(), 1.0 + std::max(3.0, allowance));
  const CliRun all =
      run("diagnose " + (dir / "rig.yaml").string() + " " + (dir / "data" / "set1").string() +
          " --only rod_compliance --rank-all --period-tolerance 0 --quiet --out " + (dir / "all").string());
  ASSERT_EQ(all.code, 0) << all.out;
  const auto ja = read_json(dir / "all" / "diagnosis.json");
  EXPECT_EQ(ja["baseline"]["numerics_allowance"].get<double>(), 0.0);
  EXPECT_EQ(ja["baseline"]["gate"].get<double>(), 4.0);
  ASSERT_EQ(ja["ranking"].size(), 1u) << ja["ranking"];
  EXPECT_EQ(ja["ranking"][0]["effect"], "rod_compliance");
  EXPECT_EQ(ja["ranking"][0]["significant"], false);
  EXPECT_EQ(ja["ranking_note"], "");
  const CliRun negative = run("diagnose " + (dir / "rig.yaml").string() + " " + (dir / "data" / "set1").string() +
                              " --period-tolerance -1e-5 --out " + (dir / "y").string());
  EXPECT_NE(negative.code, 0) << negative.out;
  EXPECT_NE(negative.out.find("--period-tolerance"), std::string::npos) << negative.out;
  EXPECT_FALSE(fs::exists(dir / "y"));
  // Rigid rods have no stiffness to be unsure of: file, line and key.
  std::ofstream(dir / "bad.yaml") << kCompareRig << "rods: {damping: 10, uncertainty: {stiffness: 0.1}}\n";
  const CliRun bad = run("diagnose " + (dir / "bad.yaml").string() + " " + (dir / "data" / "set1").string() +
                         " --out " + (dir / "x").string());
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("bad.yaml:"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("rods.uncertainty.stiffness"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(dir / "x"));
  fs::remove_all(dir);
}

// An effect the rig file already has, with its values' uncertainty: two
// load cells calibrated to +-0.5 % read 3 % high and low. diagnose names
// no missing effect, reports both gains off (the third not), prints them
// with the body and writes them to diagnosis.json.
TEST(CliDiagnose, ReportsAnEffectsValueOff) {
  const fs::path dir = fresh_dir("effect_off");
  const CliRun r = simulate_and_diagnose(
      dir, "effects:\n  load_cell_gain: {gain: [1.03, 0.97, 1.0]}\n",
      "effects:\n  load_cell_gain: {gain: 1.0, uncertainty: {gain: [0.005, 0.005, 0.005]}}\n", "rod_length_error");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("model parameter off: effects.load_cell_gain.gain[0]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("body and effects' values fitted"), std::string::npos) << r.out;
  const auto j = read_json(dir / "diag" / "diagnosis.json");
  EXPECT_TRUE(j["missing_effect"].is_null()) << j["summary"];
  EXPECT_EQ(j["model_parameters_off"],
            nlohmann::json::array({"effects.load_cell_gain.gain[0]", "effects.load_cell_gain.gain[1]"}));
  EXPECT_EQ(j["body"]["effects.load_cell_gain.gain[2]"]["off"], false);
  // Within 3 of its std or 0.2 % (the two short records' resolution) of the truth's +3 %.
  const auto& g0 = j["body"]["effects.load_cell_gain.gain[0]"];
  EXPECT_LE(std::abs(g0["offset"].get<double>() - 0.03), std::max(3 * g0["std"].get<double>(), 2e-3)) << g0;
  fs::remove_all(dir);
}

TEST_F(CliCompare, BadInputIsNamed) {
  // An unknown effect for --only.
  CliRun r = run("diagnose " + rig().string() + " " + data() + " --only gravity_waves --out " + (*dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("gravity_waves"), std::string::npos) << r.out;
  // A fitted effect out of range: file, line and key.
  std::ofstream(*dir_ / "bad.yaml") << "effects:\n  fixed_frame_flexibility:\n    joint_compliance:\n      joints: "
                                       "[[1e-6, 1e-6, 1e-6], [1e-6, -1e-6, 1e-6], [1e-6, 1e-6, 1e-6]]\n";
  r = run("compare " + rig().string() + " " + data() + " --effects " + (*dir_ / "bad.yaml").string() + " --out " +
          (*dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("bad.yaml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("joint_compliance.joints"), std::string::npos) << r.out;
  // A record in degrees: the file, the line and what to check.
  const fs::path deg = *dir_ / "deg";
  fs::create_directories(deg);
  {
    std::ifstream in(data() + "/h1.csv");
    std::ofstream outf(deg / "h1.csv");
    std::string line;
    bool header = false;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || !header) {
        header = header || (!line.empty() && line[0] != '#');
        outf << line << "\n";
        continue;
      }
      // t,F1..F3,alpha1,beta1,...: scale every angle column by 180/pi.
      std::stringstream ss(line);
      std::string cell;
      int col = 0;
      std::string row;
      while (std::getline(ss, cell, ',')) {
        double v = std::stod(cell);
        if (col >= 4) v *= 57.29577951308232;
        row += (col ? "," : "") + std::to_string(v);
        ++col;
      }
      outf << row << "\n";
    }
  }
  r = run("compare " + rig().string() + " " + (deg / "h1.csv").string() + " --out " + (*dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("h1.csv"), std::string::npos) << r.out;
  EXPECT_TRUE(r.out.find("angle") != std::string::npos || r.out.find("encoder") != std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(*dir_ / "x" / "compare.json"));
  // A record of a four-rod rig.
  r = run("compare " + (std::string(RIGFLEX_SOURCE_DIR) + "/examples/small-rig/rig.yaml") + " " + data() + " --out " +
          (*dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("h1.csv"), std::string::npos) << r.out;
}

}  // namespace
