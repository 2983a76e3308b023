// Every effects file `rigflex diagnose` writes is one `rigflex compare
// --effects` runs on: the whole catalogue fitted to records of a trifilar
// whose rod is 3 mm long (diagnose writes a file for each effect its fit
// made one of, the values as fitted, not chosen), with rigid or compliant
// rods in the model and under either integrator. diagnose itself runs once
// per kind of rods, with generalized-alpha (the file it writes does not
// depend on the integrator compare then uses);
// compare under BDF runs on one record of 6 s (the swing band's filter
// needs 5.15 s): CVODE's BDF resolves the rods' axial modes (above 100 Hz,
// rigid rods included: a stiff spring) and takes about 1.5 s of wall time
// per simulated second here, 30-100 times generalized-alpha's. So under
// BDF compare refits the body (some 20 simulations) with the first file
// only and holds it (--hold-body: one simulation) with the others; each
// file still goes through the BDF integrator and the effect's model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "apps/cli_support.hpp"
#include "apps/cli_trifilar.hpp"

namespace {

using namespace rigflex::test;

const std::string kLoopRig = cli_trifilar_rig("loop-trifilar");

struct Variant {
  const char* name;
  bool compliant_rods;  // steel rods of 1 m, 25 mm across: EA/L = 1e8 N/m
};
// ctest's test names show the parameter: its name, not its bytes.
void PrintTo(const Variant& v, std::ostream* os) { *os << v.name; }

class CliEffectFiles : public ::testing::TestWithParam<Variant> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_dir("effect_files"));
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "truth.yaml") << kLoopRig << "effects:\n  rod_length_error: {delta: [0.003, 0.0, 0.0]}\n";
    const CliRun r = run("simulate " + (*dir_ / "truth.yaml").string() + " --histories 3 --duration 8 --seed 11 --out " +
                         (*dir_ / "data").string() + " --quiet");
    ASSERT_EQ(r.code, 0) << r.out;
    const CliRun s = run("simulate " + (*dir_ / "truth.yaml").string() + " --histories 1 --duration 6 --seed 12 --out " +
                         (*dir_ / "short").string() + " --quiet");
    ASSERT_EQ(s.code, 0) << s.out;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
};
fs::path* CliEffectFiles::dir_ = nullptr;

TEST_P(CliEffectFiles, CompareRunsOnEveryFileDiagnoseWrote) {
  const Variant v = GetParam();
  const fs::path here = *dir_ / v.name;
  fs::create_directories(here);
  // Compliant rods as a rig has them, nominal (the rods block): diagnose
  // then fits a rod compliance on top of them too.
  const std::string rods = v.compliant_rods ? "rods: {stiffness: 1.0e8}\n" : "";
  const fs::path fitted = here / "fitted.yaml";
  std::ofstream(fitted) << kLoopRig << rods;
  const CliRun d = run("diagnose " + fitted.string() + " " + (*dir_ / "data" / "set1").string() + " --out " +
                       (here / "diag").string() + " --quiet");
  ASSERT_EQ(d.code, 0) << d.out;
  for (const std::string method : {"generalized-alpha", "bdf"}) {
    const fs::path rig = here / (method + ".yaml");
    std::ofstream(rig) << kLoopRig << "simulation: {method: " << method << "}\n" << rods;
    const std::string data = (*dir_ / (method == "bdf" ? "short" : "data") / "set1").string();
    std::vector<fs::path> effect_files;
    for (const auto& entry : fs::directory_iterator(here / "diag" / "effects")) effect_files.push_back(entry.path());
    std::sort(effect_files.begin(), effect_files.end());
    int files = 0;
    for (const fs::path& effects : effect_files) {
      const fs::path out = here / (method + "_compare_" + effects.stem().string());
      const bool hold = method == "bdf" && files > 0;
      const CliRun c = run("compare " + rig.string() + " " + data + " --effects " + effects.string() + " --out " +
                           out.string() + " --quiet" + (hold ? " --hold-body" : ""));
      ASSERT_EQ(c.code, 0) << method << ": " << effects << "\n" << c.out;
      std::ifstream in(out / "compare.json");
      const auto j = nlohmann::json::parse(in);
      ASSERT_TRUE(j["force_nrmse"].is_number()) << effects;
      EXPECT_TRUE(std::isfinite(j["force_nrmse"].get<double>())) << method << ": " << effects;
      ++files;
    }
    // The catalogue has ten effects, all candidates with either rods; a fit
    // that amounts to no effect (a compliance clamped at zero) writes none.
    EXPECT_GE(files, 5) << d.out;
  }
}

INSTANTIATE_TEST_SUITE_P(Rods, CliEffectFiles, ::testing::Values(Variant{"rigid", false}, Variant{"compliant", true}),
                         [](const ::testing::TestParamInfo<Variant>& i) { return std::string(i.param.name); });

}  // namespace
