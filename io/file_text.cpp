#include "io/file_text.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <limits>

#include "io/input_error.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

bool is_gzip_name(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".gz";
}

namespace {

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the file");
  // One read of the whole file: a set of 15 s logs is megabytes, and a
  // character-wise stream iterator took most of the reading time.
  std::string text;
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (!ec) {
    text.resize(static_cast<size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<size_t>(in.gcount()));
  } else {
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (in.bad()) throw InputError(file.string(), 0, "", "cannot read the file");
  return text;
}

bool has_gzip_signature(const std::string& bytes, size_t at) {
  return bytes.size() >= at + 2 && static_cast<unsigned char>(bytes[at]) == 0x1f &&
         static_cast<unsigned char>(bytes[at + 1]) == 0x8b;
}

// One gzip member from `at`; returns the offset after it.
size_t inflate_member(const std::string& in, size_t at, std::string& out, const std::string& file) {
  z_stream z{};
  // 16 + MAX_WBITS: a gzip wrapper (header and CRC checked), not zlib's.
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) throw InputError(file, 0, "", "cannot start decompression");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + at));
  const size_t available = in.size() - at;
  z.avail_in = static_cast<uInt>(std::min<size_t>(available, std::numeric_limits<uInt>::max()));
  char buffer[1 << 16];
  int status = Z_OK;
  while (status != Z_STREAM_END) {
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    status = inflate(&z, Z_NO_FLUSH);
    if (status != Z_OK && status != Z_STREAM_END) {
      const std::string why = status == Z_BUF_ERROR ? "the compressed data end too early (a truncated file?)"
                              : z.msg               ? std::string("corrupt compressed data: ") + z.msg
                                                    : "corrupt compressed data";
      inflateEnd(&z);
      throw InputError(file, 0, "", why);
    }
    out.append(buffer, sizeof buffer - z.avail_out);
    if (z.avail_in == 0 && status != Z_STREAM_END && z.avail_out != 0) {
      inflateEnd(&z);
      throw InputError(file, 0, "", "the compressed data end too early (a truncated file?)");
    }
  }
  const size_t used = available - z.avail_in;
  inflateEnd(&z);
  return at + used;
}

}  // namespace

std::string gunzip(const std::string& compressed, const std::string& file) {
  if (!has_gzip_signature(compressed, 0))
    throw InputError(file, 0, "", "not a gzip file: a .gz name, but the data do not start with gzip's signature 1f 8b");
  std::string out;
  size_t at = 0;
  while (at < compressed.size()) {
    at = inflate_member(compressed, at, out, file);
    // Padding after the last member (some tools write zeros) ends the data.
    if (!has_gzip_signature(compressed, at)) break;
  }
  return out;
}

std::string read_file_text(const fs::path& file) {
  std::string bytes = read_bytes(file);
  return is_gzip_name(file) ? gunzip(bytes, file.string()) : bytes;
}

}  // namespace rigflex::io
