#pragma once
// A study folder keeps every model version a user compares with the same
// measurements, and its errors: DIR/study.json, one entry per version (a
// version is the text of the rig file, the added effects files and the data
// files, with the options that change the errors, by an FNV-1a fingerprint;
// comparing the same version again updates its entry).
// Entries keep their first-seen order, so each new compare shows its error
// next to the earlier versions'.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigflex::report {

struct StudyEntry {
  int version = 0;           // 1, 2, ... in first-seen order
  std::string label;         // rig file and added effects files
  std::string fingerprint;   // 16 hex digits
  std::vector<std::string> effects;
  double overall_nrmse = 0, force_nrmse = 0, angle_nrmse = 0;
  std::map<std::string, double> nrmse;
  std::optional<double> identified_cog_z;  // m
};

// FNV-1a over the contents of the files, in order, and `extra` (std::runtime_error if a file cannot be read).
std::string model_fingerprint(const std::vector<std::filesystem::path>& files, const std::string& extra = "");

// The entries of DIR/study.json (none yet: empty) with `entry` added or
// updated (by fingerprint; `version` assigned). InputError naming the file
// for a study.json it cannot read. Non-finite errors are kept as NaN.
std::vector<StudyEntry> study_with(const std::filesystem::path& dir, const StudyEntry& entry);

// study_with, written back atomically under the folder's lock (waiting up
// to a minute for another run's; then InputError naming the folder and that
// run); returns the entries.
std::vector<StudyEntry> record_in_study(const std::filesystem::path& dir, const StudyEntry& entry);

// compare.json's "study": each version's label and errors, the one with
// `current_fingerprint` marked current.
nlohmann::ordered_json study_versions_json(const std::vector<StudyEntry>& entries, const std::string& current_fingerprint);

}  // namespace rigflex::report
