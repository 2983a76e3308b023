#include "io/atomic_file.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

// The temporaries being written, for removal when a signal ends the run.
// Slots hold malloc'ed C strings so that the handler only reads memory and
// calls unlink (async-signal-safe); a run has a handful of files open at
// once, and a file that finds no free slot is written unregistered.
constexpr size_t kSlots = 256;
std::array<std::atomic<char*>, kSlots> g_pending{};

}  // namespace

size_t register_temporary(const fs::path& p) {
  char* s = strdup(p.c_str());
  if (!s) return kSlots;
  for (size_t i = 0; i < kSlots; ++i) {
    char* expected = nullptr;
    if (g_pending[i].compare_exchange_strong(expected, s)) return i;
  }
  std::free(s);
  return kSlots;
}

void unregister_temporary(size_t slot) noexcept {
  if (slot < kSlots) std::free(g_pending[slot].exchange(nullptr));
}

namespace {

// Unique per process and call: two runs (or two threads) writing the same
// target do not write into each other's temporary.
fs::path temp_name(const fs::path& target, const fs::path& staging) {
  static std::atomic<unsigned long> counter{0};
  const std::string n = std::to_string(counter++);
  if (!staging.empty()) return staging / (n + "-" + target.filename().string());
  return target.string() + ".tmp-rigflex-" + std::to_string(::getpid()) + "-" + n;
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

extern "C" void remove_and_reraise(int sig) {
  remove_pending_temporaries();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void remove_pending_temporaries() noexcept {
  for (auto& slot : g_pending) {
    if (const char* p = slot.load()) ::unlink(p);
  }
  // Folders, now that their files are gone (unlink refuses a folder); a
  // folder holding another registered one empties on a later sweep.
  for (int sweep = 0; sweep < 3; ++sweep) {
    for (auto& slot : g_pending) {
      if (const char* p = slot.load()) ::rmdir(p);
    }
  }
}

void remove_temporaries_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_and_reraise);
}

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

void FileBatch::stage_in(fs::path dir) { staging_ = std::move(dir); }

std::vector<fs::path> FileBatch::targets() const {
  std::vector<fs::path> out;
  for (const auto& item : items_) out.push_back(item.first);
  return out;
}

void FileBatch::commit() {
  struct Written {
    fs::path tmp;
    size_t slot;
  };
  std::vector<Written> written;
  // The staging folder is registered first: the signal handler removes it
  // after the files written into it.
  size_t staging_slot = kSlots;
  bool staged = false;
  auto release = [&](bool remove) {
    std::error_code ec;
    for (const auto& w : written) {
      if (remove) fs::remove(w.tmp, ec);
      unregister_temporary(w.slot);
    }
    if (staged) fs::remove(staging_, ec);  // only if empty: a folder someone else filled stays
    unregister_temporary(staging_slot);
  };
  try {
    if (!staging_.empty()) {
      staging_slot = register_temporary(staging_);
      staged = fs::create_directories(staging_);
    }
    for (const auto& [target, write] : items_) {
      if (target.has_parent_path()) fs::create_directories(target.parent_path());
      const fs::path tmp = temp_name(target, staging_);
      written.push_back({tmp, register_temporary(tmp)});
      write(tmp);
      if (!fs::exists(tmp)) throw std::runtime_error("cannot write " + target.string());
    }
    for (size_t i = 0; i < items_.size(); ++i) fs::rename(written[i].tmp, items_[i].first);
  } catch (...) {
    release(true);
    throw;
  }
  release(false);
  items_.clear();
}

}  // namespace rigflex::io
