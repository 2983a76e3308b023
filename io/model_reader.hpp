#pragma once
// Reads a frame model (model.yaml) into an fe::Model, strictly: unknown keys,
// missing keys, wrong types and invalid values are InputErrors naming the
// file, line and key. The format is documented in docs/fe-core.md.
#include <filesystem>
#include <string>

#include "fe/model.hpp"

namespace rigflex::io {

struct ModelFile {
  fe::Model model;
  std::string name;  // model.name, or the file stem
};

// The file in the format its extension names (io/model_formats.hpp).
ModelFile read_model(const std::filesystem::path& file);
// `source` names the text in errors.
ModelFile parse_model(const std::string& yaml_text, const std::string& source);

}  // namespace rigflex::io
