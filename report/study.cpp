#include "report/study.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/folder_lock.hpp"
#include "io/input_error.hpp"
#include "report/json_write.hpp"

namespace rigflex::report {

// How long recording waits for another run's lock on the study folder.
constexpr double kStudyLockWaitSeconds = 60;

std::string model_fingerprint(const std::vector<std::filesystem::path>& files, const std::string& extra) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&h](const std::string& text) {
    for (unsigned char c : text + '\0') {
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + f.string());
    mix(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  }
  mix(extra);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

using Json = nlohmann::ordered_json;

double number_or_nan(const Json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

StudyEntry from_json(const Json& j) {
  StudyEntry e;
  e.version = j.at("version").get<int>();
  e.label = j.at("label").get<std::string>();
  e.fingerprint = j.at("fingerprint").get<std::string>();
  e.effects = j.value("effects", std::vector<std::string>{});
  e.overall_nrmse = number_or_nan(j, "overall_nrmse");
  e.force_nrmse = number_or_nan(j, "force_nrmse");
  e.angle_nrmse = number_or_nan(j, "angle_nrmse");
  for (const auto& [k, v] : j.at("nrmse").items()) e.nrmse[k] = v.is_number() ? v.get<double>() : std::nan("");
  if (j.contains("identified_cog_z_m") && !j["identified_cog_z_m"].is_null()) {
    e.identified_cog_z = j["identified_cog_z_m"].get<double>();
  }
  return e;
}

Json to_json(const StudyEntry& e) {
  Json j;
  j["version"] = e.version;
  j["label"] = e.label;
  j["fingerprint"] = e.fingerprint;
  j["effects"] = e.effects;
  j["overall_nrmse"] = finite_or_null(e.overall_nrmse);
  j["force_nrmse"] = finite_or_null(e.force_nrmse);
  j["angle_nrmse"] = finite_or_null(e.angle_nrmse);
  Json n = Json::object();
  for (const auto& [k, v] : e.nrmse) n[k] = finite_or_null(v);
  j["nrmse"] = n;
  j["identified_cog_z_m"] = e.identified_cog_z ? Json(*e.identified_cog_z) : Json(nullptr);
  return j;
}

}  // namespace

std::vector<StudyEntry> study_with(const std::filesystem::path& dir, const StudyEntry& added) {
  const std::filesystem::path file = dir / "study.json";
  std::vector<StudyEntry> entries;
  if (std::filesystem::exists(file)) {
    std::ifstream in(file);
    try {
      const Json j = Json::parse(in);
      for (const auto& e : j.at("versions")) entries.push_back(from_json(e));
    } catch (const Json::exception& e) {
      throw io::InputError(file.string(), 0, "versions", std::string("not a study file: ") + e.what());
    }
  }
  StudyEntry entry = added;
  bool found = false;
  for (auto& e : entries) {
    if (e.fingerprint == entry.fingerprint) {
      entry.version = e.version;
      e = entry;
      found = true;
    }
  }
  if (!found) {
    entry.version = static_cast<int>(entries.size()) + 1;
    entries.push_back(entry);
  }
  return entries;
}

std::vector<StudyEntry> record_in_study(const std::filesystem::path& dir, const StudyEntry& entry) {
  std::filesystem::create_directories(dir);
  // Read, changed and written back under the folder's lock: two compare
  // runs recording into one study at once would otherwise each write back
  // what it read, and one entry would be lost. The second waits its turn
  // (the first holds the lock for milliseconds, or, where the study is its
  // --out, for the run).
  const io::FolderLock lock(dir, "--study", kStudyLockWaitSeconds);
  const std::vector<StudyEntry> entries = study_with(dir, entry);
  Json j;
  j["versions"] = Json::array();
  for (const auto& e : entries) j["versions"].push_back(to_json(e));
  io::write_text_atomically(dir / "study.json", j.dump(2) + "\n");
  return entries;
}

nlohmann::ordered_json study_versions_json(const std::vector<StudyEntry>& entries, const std::string& current_fingerprint) {
  nlohmann::ordered_json versions = nlohmann::ordered_json::array();
  for (const auto& x : entries) {
    versions.push_back({{"version", x.version}, {"label", x.label}, {"overall_nrmse", x.overall_nrmse},
                        {"force_nrmse", x.force_nrmse}, {"angle_nrmse", x.angle_nrmse},
                        {"current", x.fingerprint == current_fingerprint}});
  }
  return versions;
}

}  // namespace rigflex::report
