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

// A child process writes a batch and is ended by SIGTERM halfway through
// its second file: the handler removes both temporaries, and the process
// still ends by the signal (its default action, not an exit code).
TEST(AtomicFile, ASignalDuringTheWriteLeavesNoTemporary) {
  const test::TempDir dir("rigflex-atomic");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    io::remove_temporaries_on_signals();
    io::FileBatch batch;
    batch.add_text(dir.path() / "a.txt", "whole");
    batch.add(dir.path() / "b.txt", [](const fs::path& p) {
      std::ofstream(p) << "half";
      std::raise(SIGTERM);
    });
    batch.commit();
    ::_exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(names_in(dir.path()).empty());
}

}  // namespace
}  // namespace rigflex
