// examples/hidden-effect as a test: the tutorial's script, run start to
// end, must find the hidden effect and show the error falling.
//  - diagnose names fixed_frame_flexibility as the missing effect, and its
//    chain stops at that stand-in;
//  - the fitted stand-in cuts the swing-band force NRMSE at least 5x and the
//    FE frame model (the proper fix) at least 5x too;
//  - the identified CoG height is within 2 mm of the truth with the FE frame
//    (and more than 20 mm off with the engineer's first model);
//  - the study folder holds the three versions in order;
//  - the reports it wrote open in headless Chromium with every plot drawn
//    and no error in the page (tests/browser/check_report.sh).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

using namespace rigflex::test;
using Json = nlohmann::json;

Json load(const fs::path& p) {
  std::ifstream in(p);
  return Json::parse(in);
}

TEST(TutorialHiddenEffect, FindsTheFrameAndTheErrorFalls) {
  const fs::path dir = fresh_dir("hidden_effect");
  const std::string script = std::string(RIGFLEX_SOURCE_DIR) + "/examples/hidden-effect/run.sh";
  const std::string cmd = "bash " + script + " " + RIGFLEX_CLI + " " + dir.string() + " > " + (dir.string() + ".log") + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << dir.string() << ".log";

  const Json diagnosis = load(dir / "diagnosis" / "diagnosis.json");
  ASSERT_TRUE(diagnosis["missing_effect"].is_string());
  EXPECT_EQ(diagnosis["missing_effect"], "fixed_frame_flexibility");
  EXPECT_EQ(diagnosis["ranking"][0]["effect"], "fixed_frame_flexibility");
  EXPECT_TRUE(diagnosis["ranking"][0]["significant"]);
  // The stand-in stays far above the noise: the chain stops there rather
  // than let further effects absorb the stand-in's own misfit.
  ASSERT_EQ(diagnosis["chain"].size(), 1u);
  EXPECT_NE(diagnosis["chain_note"].get<std::string>().find("stand-in"), std::string::npos);

  const Json first = load(dir / "compare-1" / "compare.json");
  const Json stand_in = load(dir / "compare-2" / "compare.json");
  const Json fe = load(dir / "compare-3" / "compare.json");
  const double f1 = first["force_nrmse"], f2 = stand_in["force_nrmse"], f3 = fe["force_nrmse"];
  EXPECT_GE(f1 / f2, 5.0) << f1 << " -> " << f2;
  EXPECT_GE(f1 / f3, 5.0) << f1 << " -> " << f3;
  const double true_zG = -0.598;
  EXPECT_GT(std::abs(first["identified"]["properties"]["cog"][2].get<double>() - true_zG), 0.020);
  EXPECT_LE(std::abs(fe["identified"]["properties"]["cog"][2].get<double>() - true_zG), 0.002);
  EXPECT_LE(std::abs(stand_in["identified"]["properties"]["cog"][2].get<double>() - true_zG), 0.002);

  const Json study = load(dir / "study" / "study.json");
  ASSERT_EQ(study["versions"].size(), 3u);
  EXPECT_EQ(study["versions"][0]["label"], "rig.yaml");
  EXPECT_GT(study["versions"][0]["force_nrmse"].get<double>(), study["versions"][2]["force_nrmse"].get<double>());
  for (const fs::path& html : {dir / "compare-1" / "compare.html", dir / "diagnosis" / "diagnosis.html"}) {
    std::ifstream in(html);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int plots = 0;
    for (size_t at = text.find("<canvas"); at != std::string::npos; at = text.find("<canvas", at + 1)) ++plots;
    EXPECT_GE(plots, 3) << html;
    const std::string check = "bash " + std::string(RIGFLEX_SOURCE_DIR) + "/tests/browser/check_report.sh " +
                              html.string() + " " + std::to_string(plots) + " > " + html.string() + ".log 2>&1";
    EXPECT_EQ(std::system(check.c_str()), 0) << "see " << html.string() << ".log";
  }
  RecordProperty("force_nrmse", std::to_string(f1) + " -> " + std::to_string(f2) + " -> " + std::to_string(f3));
  fs::remove_all(dir);
  fs::remove(dir.string() + ".log");
}

}  // namespace
