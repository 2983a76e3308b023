#include "io/atomic_file.hpp"

#include <fstream>
#include <stdexcept>

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {
fs::path temp_name(const fs::path& target) { return target.string() + ".tmp-rigflex"; }

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
}
}  // namespace

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  FileBatch batch;
  batch.add(target, write);
  batch.commit();
}

void write_text_atomically(const fs::path& target, const std::string& text) {
  write_atomically(target, [&](const fs::path& p) { write_text(p, text); });
}

void FileBatch::add(const fs::path& target, std::function<void(const fs::path&)> write) {
  items_.emplace_back(target, std::move(write));
}

void FileBatch::add_text(const fs::path& target, std::string text) {
  add(target, [text = std::move(text)](const fs::path& p) { write_text(p, text); });
}

void FileBatch::commit() {
  std::vector<fs::path> written;
  auto cleanup = [&] {
    std::error_code ec;
    for (const auto& p : written) fs::remove(p, ec);
  };
  try {
    for (const auto& [target, write] : items_) {
      if (target.has_parent_path()) fs::create_directories(target.parent_path());
      const fs::path tmp = temp_name(target);
      written.push_back(tmp);
      write(tmp);
      if (!fs::exists(tmp)) throw std::runtime_error("cannot write " + target.string());
    }
  } catch (...) {
    cleanup();
    throw;
  }
  for (const auto& [target, write] : items_) fs::rename(temp_name(target), target);
  items_.clear();
}

}  // namespace rigflex::io
