#pragma once
// A study folder keeps every model version a user compares with the same
// measurements, and its errors: DIR/study.json, one entry per version (a
// version is the rig file's text plus the added effects files' texts, by an
// FNV-1a fingerprint; comparing the same version again updates its entry).
// Entries keep their first-seen order, so each new compare shows its error
// next to the earlier versions'.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigflex::io {

struct StudyEntry {
  int version = 0;           // 1, 2, ... in first-seen order
  std::string label;         // rig file and added effects files
  std::string fingerprint;   // 16 hex digits
  std::vector<std::string> effects;
  double overall_nrmse = 0, force_nrmse = 0, angle_nrmse = 0;
  std::map<std::string, double> nrmse;
  std::optional<double> identified_cog_z;  // m
};

// FNV-1a over the contents of the files, in order (std::runtime_error if one cannot be read).
std::string model_fingerprint(const std::vector<std::filesystem::path>& files);

// Reads DIR/study.json (none yet: empty), adds or updates `entry` (by
// fingerprint; `version` is assigned), writes it back atomically, returns
// all entries. InputError naming the file for a study.json it cannot read.
std::vector<StudyEntry> record_in_study(const std::filesystem::path& dir, StudyEntry entry);

}  // namespace rigflex::io
