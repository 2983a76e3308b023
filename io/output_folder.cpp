#include "io/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <set>
#include <sstream>

#include "io/input_error.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

constexpr const char* kLock = ".rigflex-lock";

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

// A manifest entry is a plain relative path inside the folder.
bool safe_entry(const fs::path& p) {
  if (p.empty() || p.is_absolute()) return false;
  for (const auto& part : p) {
    if (part == "..") return false;
  }
  return true;
}

std::set<fs::path> read_manifest(const fs::path& file) {
  std::set<fs::path> out;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (const fs::path p(line); safe_entry(p)) out.insert(p);
  }
  return out;
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir, const std::string& command, std::string option)
    : dir_(std::move(dir)), manifest_(dir_ / (".rigflex-manifest-" + command)) {
  std::error_code ec;
  created_ = !fs::exists(dir_, ec);
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) throw InputError(dir_.string(), 0, option, "cannot create the output folder");
  const fs::path lock = dir_ / kLock;
  if (!try_lock(lock)) {
    const long owner = lock_owner(lock);
    if (process_alive(owner) && owner != ::getpid()) {
      throw InputError(dir_.string(), 0, option,
                       "another rigflex run (pid " + std::to_string(owner) +
                           ") is writing into this folder: wait for it, or choose another folder");
    }
    fs::remove(lock, ec);  // left by a run that was killed
    if (!try_lock(lock)) throw InputError(dir_.string(), 0, option, "cannot lock the output folder");
  }
  lock_slot_ = register_temporary(lock);
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  fs::remove(dir_ / kLock, ec);
  unregister_temporary(lock_slot_);
  // A run refused before writing leaves no folder behind that it created.
  if (created_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

void OutputFolder::commit(FileBatch& batch, const std::vector<fs::path>& also) {
  std::set<fs::path> now;
  auto relative = [&](const fs::path& target) {
    const fs::path r = target.lexically_normal().lexically_relative(dir_.lexically_normal());
    if (!safe_entry(r))
      throw std::invalid_argument("output folder: " + target.string() + " lies outside " + dir_.string());
    return r;
  };
  for (const auto& t : batch.targets()) now.insert(relative(t));
  for (const auto& t : also) now.insert(relative(t));
  batch.commit();
  std::error_code ec;
  for (const fs::path& old : read_manifest(manifest_)) {
    if (!now.count(old) && fs::is_regular_file(dir_ / old, ec)) fs::remove(dir_ / old, ec);
  }
  std::ostringstream m;
  m << "# files the last run of this rigflex command wrote here; its next run removes those it does not "
       "write again\n";
  for (const auto& p : now) m << p.generic_string() << "\n";
  write_text_atomically(manifest_, m.str());
}

}  // namespace rigflex::io
