#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

#include "io/input_error.hpp"

namespace rigflex::fuzz {

namespace {

std::filesystem::path scratch_dir() {
  // Per process: libFuzzer's -jobs/-workers run several at once. Never
  // destroyed, so that the exit handler that removes it still finds it.
  static const std::filesystem::path* dir = [] {
    const auto* d = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                              ("rigflex-fuzz-" + std::to_string(::getpid())));
    std::filesystem::create_directories(*d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(*dir, ec);
    });
    return d;
  }();
  return *dir;
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "rigflex fuzz finding: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace

void read_as_file(const std::uint8_t* data, std::size_t size, const std::string& name,
                  const std::function<void(const std::filesystem::path&)>& read) {
  const std::filesystem::path file = scratch_dir() / name;
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read(file);
  } catch (const io::InputError& e) {
    // A rig file's error may lie in a file it names; some file it must name.
    if (e.file().empty()) finding(std::string("an input error naming no file: ") + e.what());
  } catch (const std::exception& e) {
    finding(std::string("an exception other than io::InputError escaped the reader: ") + e.what());
  }
}

std::filesystem::path source_dir() { return RIGFLEX_SOURCE_DIR; }

}  // namespace rigflex::fuzz
