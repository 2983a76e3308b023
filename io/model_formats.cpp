#include "io/model_formats.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "io/abaqus_deck.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {

const std::vector<ModelFormat>& model_formats() {
  static const std::vector<ModelFormat> formats{
      {"rigflex YAML model (docs/fe-core.md)", {".yaml", ".yml"}, &parse_model},
      {"Abaqus / CalculiX input deck (docs/model-exchange.md)", {".inp"}, &parse_abaqus_deck},
  };
  return formats;
}

const ModelFormat& model_format_for(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const auto& formats = model_formats();
  for (const auto& f : formats) {
    if (std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end()) return f;
  }
  return formats.front();
}

ModelFile read_model(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return model_format_for(file).parse(ss.str(), file.string());
}

}  // namespace rigflex::io
