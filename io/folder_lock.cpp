#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <thread>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

bool process_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

long lock_owner(const fs::path& lock) {
  std::ifstream in(lock);
  long pid = 0;
  in >> pid;
  return pid;
}

// O_EXCL: exactly one of two runs starting at once creates the file.
bool try_lock(const fs::path& lock) {
  const int fd = ::open(lock.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return false;
  const std::string pid = std::to_string(::getpid()) + "\n";
  const bool ok = ::write(fd, pid.data(), pid.size()) == static_cast<ssize_t>(pid.size());
  ::close(fd);
  return ok;
}

}  // namespace

FolderLock::FolderLock(fs::path dir, const std::string& option, double wait_seconds) : file_(dir / kFileName) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(wait_seconds);
  bool unnamed = false;  // the file names no pid: since when
  Clock::time_point unnamed_since;
  while (!try_lock(file_)) {
    const long owner = lock_owner(file_);
    if (owner == ::getpid()) return;  // held by this run already (a study kept in its own --out)
    std::error_code ec;
    if (owner > 0 && !process_alive(owner)) {
      fs::remove(file_, ec);  // left by a run that was killed
      continue;
    }
    if (owner > 0) {
      if (Clock::now() >= deadline) {
        throw InputError(dir.string(), 0, option,
                         "another rigflex run (pid " + std::to_string(owner) +
                             ") is writing into this folder: wait for it, or choose another folder");
      }
    } else {
      // No pid yet: a run that has just created the file and is writing it,
      // or one killed in between. Taken over once it stays so for a second.
      if (!unnamed) unnamed = true, unnamed_since = Clock::now();
      if (Clock::now() - unnamed_since > std::chrono::seconds(1)) {
        fs::remove(file_, ec);
        unnamed = false;
        continue;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  owned_ = true;
  slot_ = register_temporary(file_);
}

FolderLock::~FolderLock() {
  if (!owned_) return;
  std::error_code ec;
  fs::remove(file_, ec);
  unregister_temporary(slot_);
}

}  // namespace rigflex::io
