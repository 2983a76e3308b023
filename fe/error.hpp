#pragma once
#include <stdexcept>
#include <string>

namespace rigflex::fe {

// What part of a model an error is about, so that the input layer can point
// at the file and line that defined it.
struct EntityRef {
  std::string kind;  // "node", "material", "beam_section", "shell_section", "beam", "shell", ...
  std::string id;    // the entity's id or index as the user wrote it
  std::string key;   // the offending field, if known
};

// Invalid model content (non-positive E, missing node, degenerate element...).
class ModelError : public std::runtime_error {
 public:
  ModelError(EntityRef where, const std::string& message)
      : std::runtime_error(message), where_(std::move(where)) {}
  const EntityRef& where() const { return where_; }

 private:
  EntityRef where_;
};

}  // namespace rigflex::fe
