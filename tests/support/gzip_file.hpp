#pragma once
// Writes test files gzip-compressed, through zlib itself (an independent
// writer for rigflex's .gz reading).
#include <zlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace rigflex::test {

inline void write_gzip(const std::filesystem::path& p, const std::string& text, const char* mode = "wb") {
  gzFile f = gzopen(p.string().c_str(), mode);
  if (!f) throw std::runtime_error("cannot write " + p.string());
  const int written = text.empty() ? 0 : gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  if (gzclose(f) != Z_OK || written != static_cast<int>(text.size()))
    throw std::runtime_error("cannot write " + p.string());
}

}  // namespace rigflex::test
