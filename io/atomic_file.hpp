#pragma once
// Output files appear whole or not at all: each is written to a temporary
// name beside its destination and renamed into place.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rigflex::io {

// Calls write(temp_path), then renames temp_path to `target`. On any
// exception the temporary file is removed and the exception rethrown.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);
void write_text_atomically(const std::filesystem::path& target, const std::string& text);

// Temporaries are named uniquely (process and call), so two runs writing
// into one folder never share one. While written, each is registered:
// remove_pending_temporaries() unlinks every registered one and is
// async-signal-safe; remove_temporaries_on_signals() installs it for
// SIGINT, SIGTERM and SIGHUP (then the signal's default action: the process
// ends as it would have), for a command line to call once. A library never
// installs it by itself. A registered folder is removed after the files in
// it (rmdir: only once empty).
void remove_pending_temporaries() noexcept;
void remove_temporaries_on_signals();
// Registers another file for removal on those signals (an output folder's
// lock); returns the slot to give back when the file is gone.
size_t register_temporary(const std::filesystem::path& file);
void unregister_temporary(size_t slot) noexcept;

// A set of files committed together: all are written to temporary names
// first and renamed only after every one succeeded.
class FileBatch {
 public:
  void add(const std::filesystem::path& target, std::function<void(const std::filesystem::path&)> write);
  void add_text(const std::filesystem::path& target, std::string text);
  // Writes the temporaries into `dir` (created for the commit and removed
  // after it; on the targets' file system) instead of beside each target:
  // a run killed outright leaves its debris in that one folder, not among
  // the results.
  void stage_in(std::filesystem::path dir);
  void commit();  // throws std::runtime_error naming the file that failed
  std::vector<std::filesystem::path> targets() const;

 private:
  std::vector<std::pair<std::filesystem::path, std::function<void(const std::filesystem::path&)>>> items_;
  std::filesystem::path staging_;
};

}  // namespace rigflex::io
