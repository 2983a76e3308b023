#pragma once
// The folder a run writes its results into (--out). While the run lasts it
// holds a lock (`.rigflex-lock`, the run's pid): a second run into the same
// folder is refused at its start, with the pid, instead of the two mixing
// their files. When the results are committed, the files an earlier run of
// the same command wrote there (listed in `.rigflex-manifest-COMMAND`) and
// this one did not are removed - a second `modes` run with fewer modes no
// longer leaves the first run's extra mode files - while anything else in
// the folder (another command's results, the user's files) is left alone. A lock whose process has ended (a run killed
// with SIGKILL) is taken over; SIGINT/SIGTERM remove it with the temporaries (io/atomic_file.hpp).
#include <filesystem>
#include <string>

#include "io/atomic_file.hpp"

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
  size_t lock_slot_;
};

}  // namespace rigflex::io
