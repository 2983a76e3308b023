#include "io/output_folder.hpp"

#include <unistd.h>

#include <fstream>
#include <set>
#include <sstream>

#include "io/input_error.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

constexpr const char* kStagingPrefix = ".rigflex-run-";

// Every staging folder in a locked folder is left by a run that was killed
// outright: while the lock is held, no other run writes there.
void remove_stale_staging(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().filename().string().rfind(kStagingPrefix, 0) == 0 && e.is_directory(ec)) fs::remove_all(e.path(), ec);
  }
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
  try {
    lock_.emplace(dir_, option);
  } catch (...) {
    if (created_) fs::remove(dir_, ec);
    throw;
  }
  remove_stale_staging(dir_);
  // A signal that ends the run leaves no empty folder it created behind.
  if (created_) created_slot_ = register_temporary(dir_);
}

OutputFolder::~OutputFolder() {
  lock_.reset();
  if (created_) unregister_temporary(created_slot_);
  std::error_code ec;
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
  const fs::path staging = dir_ / (kStagingPrefix + std::to_string(::getpid()));
  batch.stage_in(staging);
  batch.commit();
  std::error_code ec;
  for (const fs::path& old : read_manifest(manifest_)) {
    if (!now.count(old) && fs::is_regular_file(dir_ / old, ec)) fs::remove(dir_ / old, ec);
  }
  std::ostringstream m;
  m << "# files the last run of this rigflex command wrote here; its next run removes those it does not "
       "write again\n";
  for (const auto& p : now) m << p.generic_string() << "\n";
  FileBatch manifest;
  manifest.add_text(manifest_, m.str());
  manifest.stage_in(staging);
  manifest.commit();
}

}  // namespace rigflex::io
