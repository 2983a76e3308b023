#pragma once
// What every fuzz target of tests/fuzz shares: the bytes libFuzzer made,
// written to a file (the readers take files, as the commands do), handed to
// one reader, and the outcome judged by rigflex's promise for bad input
// (docs/reliability.md): the reader returns, or throws io::InputError naming
// the file. Any other exception is a finding: an internal error that would
// reach a user as exit 3 with no file named.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace rigflex::fuzz {

// Writes `data` to a file named `name` in this process's scratch folder and
// calls `read` on its path. Aborts (a libFuzzer crash, the input kept) when
// `read` throws anything but io::InputError, or an InputError that names no
// file.
void read_as_file(const std::uint8_t* data, std::size_t size, const std::string& name,
                  const std::function<void(const std::filesystem::path&)>& read);

// The folder the targets' fixed inputs come from (examples/, tests/bad-input).
std::filesystem::path source_dir();

}  // namespace rigflex::fuzz
