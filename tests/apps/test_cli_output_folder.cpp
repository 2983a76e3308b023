// The output folder: a later run removes the files an earlier one wrote and
// it did not write again, leaves the user's own files, and a folder locked
// by a live run is refused while a lock left by a killed run is taken over.
#include <gtest/gtest.h>
#include <unistd.h>

#include <set>
#include <string>

#include "cli_support.hpp"

namespace rigflex::test {
namespace {

const std::string kModel = std::string(RIGFLEX_SOURCE_DIR) + "/tests/bad-input/valid-model.yaml";

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

TEST(CliOutputFolder, ASecondRunReplacesTheFirstRunsFilesAndKeepsTheUsers) {
  const fs::path out = fresh_dir("output_folder_modes");
  ASSERT_EQ(run("modes " + kModel + " --count 4 --quiet --out " + out.string()).code, 0);
  EXPECT_TRUE(fs::exists(out / "mode_004.vtu"));
  std::ofstream(out / "notes.txt") << "the user's own file\n";
  const CliRun r = run("modes " + kModel + " --count 2 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(names_in(out), (std::set<std::string>{".rigflex-manifest-modes", "mode_001.vtu", "mode_002.vtu",
                                                  "modes.json", "modes.pvd", "notes.txt"}));
  // Another command's results in the same folder are not the modes run's to remove.
  ASSERT_EQ(run("reduce " + example("beam-frame") + " --interface upper_joints --quiet --out " + out.string()).code, 0);
  ASSERT_EQ(run("modes " + kModel + " --count 3 --quiet --out " + out.string()).code, 0);
  EXPECT_TRUE(fs::exists(out / "reduced.json"));
  EXPECT_TRUE(fs::exists(out / "mode_003.vtu"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  fs::remove_all(out);
}

TEST(CliOutputFolder, AFolderALiveRunHoldsIsRefusedAndAKilledRunsLockTakenOver) {
  const fs::path out = fresh_dir("output_folder_lock");
  fs::create_directories(out);
  std::ofstream(out / ".rigflex-lock") << ::getpid() << "\n";  // this test process: alive
  const CliRun refused = run("modes " + kModel + " --count 2 --quiet --out " + out.string());
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("another rigflex run (pid " + std::to_string(::getpid()) + ")"), std::string::npos)
      << refused.out;
  EXPECT_EQ(names_in(out), std::set<std::string>{".rigflex-lock"});  // nothing written, the lock left to its owner

  // A pid no process has (above the kernel's pid_max of 2^22): a killed run's lock.
  { std::ofstream(out / ".rigflex-lock") << 99999999 << "\n"; }
  const CliRun taken = run("modes " + kModel + " --count 2 --quiet --out " + out.string());
  EXPECT_EQ(taken.code, 0) << taken.out;
  EXPECT_TRUE(fs::exists(out / "modes.json"));
  EXPECT_FALSE(fs::exists(out / ".rigflex-lock"));  // released at the end of the run
  fs::remove_all(out);
}

}  // namespace
}  // namespace rigflex::test
