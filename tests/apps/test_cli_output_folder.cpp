// The output folder: a later run removes the files an earlier one wrote and
// it did not write again, leaves the user's own files, and a folder locked
// by a live run is refused while a lock left by a killed run is taken over.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
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

// A run killed outright (SIGKILL: no handler runs) leaves its staging
// folder with a half-written file; the next run into the folder removes it,
// and the results never held the half-written file.
TEST(CliOutputFolder, AKilledRunsStagingFolderIsRemovedByTheNext) {
  const fs::path out = fresh_dir("output_folder_staging");
  fs::create_directories(out / ".rigflex-run-99999999");
  { std::ofstream(out / ".rigflex-run-99999999" / "3-mode_001.vtu") << "<VTKFile half"; }
  const CliRun r = run("modes " + kModel + " --count 2 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(names_in(out), (std::set<std::string>{".rigflex-manifest-modes", "mode_001.vtu", "mode_002.vtu",
                                                  "modes.json", "modes.pvd"}));
  fs::remove_all(out);
}

// Ctrl-C while a run works: it ends by the signal, and the folder holds
// what it held before - the lock, the staging folder and a folder the run
// created are gone; an earlier run's results and the user's file are kept.
fs::path interrupted_simulation(const fs::path& out) {
  const std::string rig = std::string(RIGFLEX_SOURCE_DIR) + "/examples/small-rig/rig.yaml";
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(RIGFLEX_CLI, RIGFLEX_CLI, "simulate", rig.c_str(), "--sets", "1", "--histories", "4", "--duration", "3000",
            "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  EXPECT_GT(child, 0);
  // Interrupted once it has locked the folder: at work, not yet writing
  // (the records are written when all are simulated: minutes from here).
  for (int k = 0; k < 400 && !fs::exists(out / ".rigflex-lock"); ++k) ::usleep(50000);
  EXPECT_TRUE(fs::exists(out / ".rigflex-lock"));
  ::usleep(300000);
  ::kill(child, SIGINT);
  int status = 0;
  EXPECT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  return out;
}

TEST(CliOutputFolder, CtrlCLeavesTheFolderAsItWas) {
  const fs::path fresh = fresh_dir("output_folder_sigint_new");
  interrupted_simulation(fresh);
  EXPECT_FALSE(fs::exists(fresh));  // created by the run, removed with it

  const fs::path kept = fresh_dir("output_folder_sigint_kept");
  ASSERT_EQ(run("modes " + kModel + " --count 2 --quiet --out " + kept.string()).code, 0);
  std::ofstream(kept / "notes.txt") << "the user's own file\n";
  const std::set<std::string> before = names_in(kept);
  interrupted_simulation(kept);
  EXPECT_EQ(names_in(kept), before);
  fs::remove_all(kept);
}

}  // namespace
}  // namespace rigflex::test
