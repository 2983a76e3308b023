#pragma once
// One rigflex run at a time in a folder: `.rigflex-lock` holds the pid of
// the run that writes there. A second run is refused (or waits, for files
// that are only read, changed and written back in a moment, like a study's
// record); a lock whose process has ended (killed with SIGKILL) is taken
// over; SIGINT/SIGTERM remove it with the temporaries (io/atomic_file.hpp).
#include <filesystem>
#include <string>

namespace rigflex::io {

class FolderLock {
 public:
  // Locks `dir` (which must exist). If another live run holds it: waits up
  // to `wait_seconds` (0: not at all), then throws InputError (file `dir`,
  // key `option`) naming that run's pid. A lock this process already holds
  // is shared: the inner FolderLock leaves it to the outer one.
  FolderLock(std::filesystem::path dir, const std::string& option, double wait_seconds = 0);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  static constexpr const char* kFileName = ".rigflex-lock";

 private:
  std::filesystem::path file_;
  bool owned_ = false;
  size_t slot_ = 0;
};

}  // namespace rigflex::io
