#include <algorithm>
#include <string>
#include <string_view>
#include <utility>

#include "io/measurement_csv.hpp"
#include "io/measurement_reader.hpp"
#include "io/measurement_text.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;
using measurement_text::lower;

// A measurement file: *.csv, or *.csv.gz read through its decompression (any case).
bool is_measurement_name(const std::string& name) {
  const std::string n = lower(name);
  return n.ends_with(".csv") || n.ends_with(".csv.gz");
}

// Digit runs compare by value, everything else byte by byte, so h2 < h10.
int natural_compare(std::string_view a, std::string_view b) {
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      std::string_view x = a.substr(i, ie - i), y = b.substr(j, je - j);
      while (x.size() > 1 && x.front() == '0') x.remove_prefix(1);
      while (y.size() > 1 && y.front() == '0') y.remove_prefix(1);
      if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;
      if (const int c = x.compare(y); c != 0) return c;
      i = ie, j = je;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]) ? -1 : 1;
    ++i, ++j;
  }
  if (i < a.size()) return 1;
  if (j < b.size()) return -1;
  return 0;
}

// Equal by value ("h01", "h1"): byte order decides, so the order is total.
bool natural_less(const std::string& a, const std::string& b) {
  const int c = natural_compare(a, b);
  return c != 0 ? c < 0 : a < b;
}

std::vector<fs::path> csv_files(const fs::path& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) throw InputError(folder.string(), 0, "", "no such folder");
  if (!fs::is_directory(folder, ec)) throw InputError(folder.string(), 0, "", "not a folder");
  std::vector<fs::path> files;
  try {
    for (const auto& entry : fs::directory_iterator(folder)) {
      const std::string name = entry.path().filename().string();
      // Hidden files are skipped: copies to a USB stick leave "._h1.csv" beside "h1.csv".
      if (name.empty() || name.front() == '.') continue;
      if (!is_measurement_name(name) || !entry.is_regular_file()) continue;
      files.push_back(entry.path());
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(folder.string(), 0, "", std::string("cannot list the folder: ") + e.code().message());
  }
  if (files.empty()) throw InputError(folder.string(), 0, "", "no .csv or .csv.gz files in the folder");
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

}  // namespace

MeasurementSet read_measurement_set(const fs::path& folder, int expected_rods) {
  MeasurementSet set;
  set.files = csv_files(folder);
  for (const auto& file : set.files) {
    // Every file must have the rods of the first, when the caller did not say how many.
    RodRule rule{expected_rods, ""};
    if (expected_rods == 0 && !set.records.empty())
      rule = {set.records.front().rods(), ", as in " + set.files.front().filename().string()};
    set.records.push_back(read_measurement_file(file, rule));
  }
  return set;
}

namespace {

bool holds_csv(const fs::path& folder) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() != '.' && is_measurement_name(name) && entry.is_regular_file())
      return true;
  }
  return false;
}

std::vector<fs::path> set_folders(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() != '.' && entry.is_directory() && holds_csv(entry.path()))
      out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return out;
}

}  // namespace

MeasurementSets read_measurement_sets(const std::vector<fs::path>& paths, int expected_rods) {
  MeasurementSets out;
  MeasurementSet loose;
  for (const auto& path : paths) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path.string(), 0, "", "no such file or folder");
    if (!fs::is_directory(path, ec)) {
      loose.files.push_back(path);
      loose.records.push_back(read_record_csv(path, expected_rods));
      continue;
    }
    if (holds_csv(path)) {
      out.names.push_back(path.string());
      out.sets.push_back(read_measurement_set(path, expected_rods));
      continue;
    }
    const auto folders = set_folders(path);
    if (folders.empty()) throw InputError(path.string(), 0, "", "no .csv or .csv.gz files in the folder or its subfolders");
    for (const auto& f : folders) {
      out.names.push_back(f.string());
      out.sets.push_back(read_measurement_set(f, expected_rods));
    }
  }
  if (!loose.files.empty()) {
    out.names.push_back("files");
    out.sets.push_back(std::move(loose));
  }
  return out;
}

}  // namespace rigflex::io
