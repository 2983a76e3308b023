// A study folder is read, changed and written back by every compare run
// that records into it: runs recording at once take turns under the
// folder's lock, so that none writes back an older read over another's entry.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/folder_lock.hpp"
#include "io/input_error.hpp"
#include "report/study.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;

report::StudyEntry entry(const std::string& fingerprint) {
  report::StudyEntry e;
  e.label = "rig.yaml";
  e.fingerprint = fingerprint;
  e.overall_nrmse = 0.01;
  return e;
}

// Two processes record 25 versions each into one study as fast as they
// can. Without the lock a read-modify-write that overlaps another loses
// the other's entry (26-30 of the 50 were kept, in 5 runs of 5 with the
// lock taken out); with it, every one of the 50 is there.
TEST(StudyLock, TwoRunsRecordingAtOnceLoseNoEntry) {
  const test::TempDir dir("rigflex-study");
  constexpr int kEach = 25;
  pid_t children[2];
  for (int c = 0; c < 2; ++c) {
    children[c] = ::fork();
    ASSERT_GE(children[c], 0);
    if (children[c] == 0) {
      int code = 0;
      try {
        for (int i = 0; i < kEach; ++i)
          report::record_in_study(dir.path(), entry(std::to_string(c) + "-" + std::to_string(i)));
      } catch (...) {
        code = 1;
      }
      ::_exit(code);
    }
  }
  for (pid_t child : children) {
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
  }
  const nlohmann::json study = nlohmann::json::parse(std::ifstream(dir.path() / "study.json"));
  EXPECT_EQ(study["versions"].size(), 2u * kEach);
  EXPECT_FALSE(fs::exists(dir.path() / io::FolderLock::kFileName));
}

// The study kept in the run's own --out: the lock this process holds is shared.
TEST(StudyLock, AStudyInTheRunsOwnLockedFolderIsRecorded) {
  const test::TempDir dir("rigflex-study");
  {
    const io::FolderLock out(dir.path(), "--out");
    report::record_in_study(dir.path(), entry("a"));
    EXPECT_TRUE(fs::exists(dir.path() / io::FolderLock::kFileName));  // still the outer lock's
  }
  EXPECT_FALSE(fs::exists(dir.path() / io::FolderLock::kFileName));
  EXPECT_TRUE(fs::exists(dir.path() / "study.json"));
}

// A live process other than this one holds the folder (the test's parent
// process stands in for it): a lock that does not wait is refused with its
// pid; a lock that waits gets the folder once the holder lets go.
TEST(FolderLockTest, ALiveHolderIsNamedAndWaitedFor) {
  const test::TempDir dir("rigflex-lock");
  const fs::path file = dir.path() / io::FolderLock::kFileName;
  { std::ofstream(file) << ::getppid() << "\n"; }
  try {
    const io::FolderLock refused(dir.path(), "--study");
    ADD_FAILURE() << "locked a folder a live process holds";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(::getppid())), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--study"), std::string::npos) << e.what();
  }
  const pid_t releaser = ::fork();
  ASSERT_GE(releaser, 0);
  if (releaser == 0) {
    ::usleep(200000);
    fs::remove(file);
    ::_exit(0);
  }
  {
    const io::FolderLock waited(dir.path(), "--study", 30);
    std::ifstream in(file);
    long owner = 0;
    in >> owner;
    EXPECT_EQ(owner, ::getpid());
  }
  int status = 0;
  ASSERT_EQ(::waitpid(releaser, &status, 0), releaser);
  EXPECT_FALSE(fs::exists(file));
}

// A lock file that names no run (a run killed between creating and writing
// it) is taken over after a second rather than refusing the folder forever.
TEST(FolderLockTest, ALockNamingNoRunIsTakenOver) {
  const test::TempDir dir("rigflex-lock");
  const fs::path file = dir.path() / io::FolderLock::kFileName;
  { std::ofstream(file) << ""; }
  const io::FolderLock lock(dir.path(), "--out");
  std::ifstream in(file);
  long owner = 0;
  in >> owner;
  EXPECT_EQ(owner, ::getpid());
}

}  // namespace
}  // namespace rigflex
