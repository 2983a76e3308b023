#pragma once
// A data file's whole text, read in one go; a name ending in .gz is
// inflated on the way (rig logs are often archived compressed), so every
// reader that takes its text from here reads .csv.gz as it reads .csv.
#include <filesystem>
#include <string>

namespace rigflex::io {

// True for names ending in ".gz" (any case).
bool is_gzip_name(const std::filesystem::path& file);

// The file's bytes, inflated when is_gzip_name(file) (several gzip members
// are read one after the other, as gzip itself does). Throws InputError
// naming the file when it cannot be opened or read, when a .gz file does not
// start with the gzip signature, or when its compressed data are corrupt or
// cut short.
std::string read_file_text(const std::filesystem::path& file);

// `compressed` inflated; `file` names it in errors.
std::string gunzip(const std::string& compressed, const std::string& file);

}  // namespace rigflex::io
