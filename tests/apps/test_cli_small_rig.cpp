// examples/small-rig end to end: the stiff quadrifilar rig (300 kg engine,
// fixed frame reduced in-process by Craig-Bampton) passes the design check
// with a wide margin and simulates with four load cells and four encoders.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_support.hpp"

namespace {

using namespace rigflex::test;

std::string small_rig() { return std::string(RIGFLEX_SOURCE_DIR) + "/examples/small-rig/rig.yaml"; }

TEST(CliSmallRig, CheckIsSafeWithRatioWellAboveFour) {
  const fs::path out = fresh_dir("small_rig_check");
  const CliRun r = run("check " + small_rig() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(out / "check.json");
  ASSERT_TRUE(in) << "no check.json in " << out;
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["rig"].get<std::string>(), "small-rig");
  EXPECT_EQ(j["verdict"].get<std::string>(), "rigid identification safe");
  const double ratio = j["ratio"].get<double>();
  EXPECT_GT(ratio, 4.0);
  // Consistent with the frequencies it comes from: f1 / highest swing.
  const auto swing = j["swing_frequencies_hz"].get<std::vector<double>>();
  ASSERT_EQ(swing.size(), 3u);  // two sways and the yaw
  const double f1 = j["first_deformation_frequency_hz"].get<double>();
  EXPECT_NEAR(ratio, f1 / *std::max_element(swing.begin(), swing.end()), 1e-9 * ratio);
  // The first deformation mode is the fixed frame's (the only flexible part).
  EXPECT_GT(j["strain_energy_share"]["fixed_frame"].get<double>(), 0.5);
  EXPECT_LT(j["equilibrium"]["residual"].get<double>(), 1e-6);
  EXPECT_TRUE(fs::exists(out / "rig_modes.pvd"));
  fs::remove_all(out);
}

TEST(CliSmallRig, SimulateWritesFourLoadCellsAndEncoders) {
  const fs::path out = fresh_dir("small_rig_meas");
  const CliRun r = run("simulate " + small_rig() + " --sets 1 --histories 1 --duration 1 --seed 3 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(out / "set1" / "h1.csv");
  ASSERT_TRUE(in) << r.out;
  std::string line, header;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = line;
      continue;
    }
    std::stringstream ss(line);
    std::vector<double> v;
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
    rows.push_back(v);
  }
  EXPECT_EQ(header, "t,F1,F2,F3,F4,alpha1,beta1,alpha2,beta2,alpha3,beta3,alpha4,beta4");
  ASSERT_EQ(rows.size(), 501u);  // 1 s at 500 Hz, both ends
  // The four rods share the weight of the engine and the rods (load cells at
  // the upper rod end read the whole rod weight): 300 kg + 4 x 2 kg.
  double mean = 0;
  for (const auto& v : rows) mean += v[1] + v[2] + v[3] + v[4];
  mean /= static_cast<double>(rows.size());
  EXPECT_NEAR(mean / (308.0 * 9.80665), 1.0, 0.02);
  for (const auto& v : rows) {
    for (int i = 1; i <= 4; ++i) EXPECT_GT(v[static_cast<size_t>(i)], 0.0);  // every rod in tension
  }
  fs::remove_all(out);
}

}  // namespace
