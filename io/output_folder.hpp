#pragma once
// The folder a run writes its results into (--out). While the run lasts it
// is locked (io/folder_lock.hpp): a second run into the same folder is
// refused at its start, with the pid, instead of the two mixing their
// files. The run's files are written into a private folder inside it
// (`.rigflex-run-PID`) and moved into place together when all are written;
// a run killed outright leaves only that folder, which the next run into
// the folder removes. When the results are committed, the files an earlier
// run of the same command wrote there (listed in
// `.rigflex-manifest-COMMAND`) and this one did not are removed - a second
// `modes` run with fewer modes no longer leaves the first run's extra mode
// files - while anything else in the folder (another command's results,
// the user's files) is left alone.
#include <filesystem>
#include <optional>
#include <string>

#include "io/atomic_file.hpp"
#include "io/folder_lock.hpp"

namespace rigflex::io {

class OutputFolder {
 public:
  // Creates the folder if needed and locks it; InputError (key `option`)
  // when another live run holds it.
  OutputFolder(std::filesystem::path dir, const std::string& command, std::string option = "--out");
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  // Commits `batch` (its files must lie inside the folder), then removes the
  // files of the last manifest not written again and writes the new one.
  // `also`: files this run wrote into the folder by other means (a report
  // written on its own), kept in the manifest.
  void commit(FileBatch& batch, const std::vector<std::filesystem::path>& also = {});

 private:
  std::filesystem::path dir_, manifest_;
  bool created_ = false;
  std::optional<FolderLock> lock_;
  size_t created_slot_ = 0;
};

}  // namespace rigflex::io
