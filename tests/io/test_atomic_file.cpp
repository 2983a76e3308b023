// Output files appear whole or not at all: unique temporaries, nothing left
// after a failed write, and nothing left when a signal ends the run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "io/atomic_file.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

TEST(AtomicFile, TwoBatchesGetTheirOwnTemporaries) {
  const test::TempDir dir("rigflex-atomic");
  fs::path first, second;
  io::FileBatch a, b;
  a.add(dir.path() / "out.txt", [&](const fs::path& p) { first = p, std::ofstream(p) << "a"; });
  b.add(dir.path() / "out.txt", [&](const fs::path& p) { second = p, std::ofstream(p) << "b"; });
  a.commit();
  b.commit();
  EXPECT_NE(first, second);
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"out.txt"});
}

TEST(AtomicFile, AFailedWriteLeavesNothing) {
  const test::TempDir dir("rigflex-atomic");
  io::FileBatch batch;
  batch.add_text(dir.path() / "a.txt", "whole");
  batch.add(dir.path() / "b.txt", [](const fs::path& p) {
    std::ofstream(p) << "half";
    throw std::runtime_error("disk full");
  });
  EXPECT_THROW(batch.commit(), std::runtime_error);
  EXPECT_TRUE(names_in(dir.path()).empty());
}

// A child process writes a batch (into `staging` if given) and is ended by
// SIGTERM halfway through its second file; returns its wait status.
int status_of_a_writer_ended_mid_write(const fs::path& dir, const fs::path& staging = {}) {
  const pid_t child = ::fork();
  if (child == 0) {
    io::remove_temporaries_on_signals();
    io::FileBatch batch;
    batch.add_text(dir / "a.txt", "whole");
    batch.add(dir / "b.txt", [](const fs::path& p) {
      std::ofstream(p) << "half";
      std::raise(SIGTERM);
    });
    if (!staging.empty()) batch.stage_in(staging);
    batch.commit();
    ::_exit(0);  // not reached
  }
  int status = 0;
  EXPECT_GT(child, 0);
  EXPECT_EQ(::waitpid(child, &status, 0), child);
  return status;
}

// The handler removes both temporaries, and the process still ends by the
// signal (its default action, not an exit code).
TEST(AtomicFile, ASignalDuringTheWriteLeavesNoTemporary) {
  const test::TempDir dir("rigflex-atomic");
  const int status = status_of_a_writer_ended_mid_write(dir.path());
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(names_in(dir.path()).empty());
}

// Staged in a private folder: the temporaries are written there, not
// beside the results, and the folder is gone after the commit - and after a
// failed one.
TEST(AtomicFile, AStagedBatchWritesInItsFolderAndRemovesIt) {
  const test::TempDir dir("rigflex-atomic");
  const fs::path staging = dir.path() / ".rigflex-run-1";
  fs::path temporary;
  io::FileBatch batch;
  batch.add(dir.path() / "sub" / "a.txt", [&](const fs::path& p) { temporary = p, std::ofstream(p) << "a"; });
  batch.stage_in(staging);
  batch.commit();
  EXPECT_EQ(temporary.parent_path(), staging);
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"sub"});
  EXPECT_EQ(names_in(dir.path() / "sub"), std::set<std::string>{"a.txt"});

  io::FileBatch failed;
  failed.add_text(dir.path() / "b.txt", "whole");
  failed.add(dir.path() / "c.txt", [](const fs::path&) { throw std::runtime_error("disk full"); });
  failed.stage_in(staging);
  EXPECT_THROW(failed.commit(), std::runtime_error);
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"sub"});
}

// SIGTERM in the middle of a staged batch: the files and then the staging
// folder are removed by the handler.
TEST(AtomicFile, ASignalDuringAStagedWriteLeavesNoFolder) {
  const test::TempDir dir("rigflex-atomic");
  const int status = status_of_a_writer_ended_mid_write(dir.path(), dir.path() / ".rigflex-run-2");
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(names_in(dir.path()).empty());
}

}  // namespace
}  // namespace rigflex
