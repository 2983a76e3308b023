#pragma once
// The model file formats rigflex reads, one table entry each: read_model
// picks the entry by the file's extension (case-insensitive), and a file
// whose extension no entry claims is read as the first entry's format, the
// rigflex YAML model. docs/extending.md: adding a format is one entry here
// plus its parser.
#include <filesystem>
#include <string>
#include <vector>

#include "io/model_reader.hpp"

namespace rigflex::io {

struct ModelFormat {
  std::string name;                     // for messages and docs
  std::vector<std::string> extensions;  // lower case, with the dot
  // Parses a whole file's text; `source` names it in errors (InputError).
  ModelFile (*parse)(const std::string& text, const std::string& source);
};

const std::vector<ModelFormat>& model_formats();
const ModelFormat& model_format_for(const std::filesystem::path& file);

}  // namespace rigflex::io
