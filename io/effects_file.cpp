#include "io/effects_file.hpp"

#include <sstream>

namespace rigflex::io {

std::string effects_file_text(const std::vector<std::string>& comments, const std::string& blocks) {
  std::string s;
  for (const auto& c : comments) s += "# " + c + "\n";
  s += "effects:\n";
  std::istringstream lines(blocks);
  for (std::string line; std::getline(lines, line);) s += "  " + line + "\n";
  return s;
}

}  // namespace rigflex::io
