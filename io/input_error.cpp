#include "io/input_error.hpp"

namespace rigflex::io {
namespace {
std::string compose(const std::string& file, int line, const std::string& key, const std::string& message) {
  // Built by appends: GCC 12 warns falsely (-Wrestrict) on "x" + std::string temporaries here.
  std::string s = file;
  if (line > 0) s.append(":").append(std::to_string(line));
  s.append(": ");
  if (!key.empty()) s.append("key '").append(key).append("': ");
  return s.append(message);
}
}  // namespace

InputError::InputError(std::string file, int line, std::string key, const std::string& message)
    : std::runtime_error(compose(file, line, key, message)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)),
      reason_(message) {}

}  // namespace rigflex::io
