#pragma once
// Strict reading of a JSON document: every value knows its path
// ("checks.frequencies[2].mac") and line, so that a missing key, a wrong type
// or an invalid value names the file, the line and the key. nlohmann::json
// keeps no positions; the lines are recorded while parsing.
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "io/input_error.hpp"

namespace rigflex::io {

// A value of the document and its path from the root ("" for the root).
struct JsonNode {
  const nlohmann::json* value = nullptr;
  std::string path;
};

class JsonFields {
 public:
  // Malformed JSON throws InputError with the line of the error.
  JsonFields(const std::string& text, std::string file);
  // Reads the file; InputError if it cannot be opened.
  static JsonFields from_file(const std::string& file);

  const std::string& file() const { return file_; }
  JsonNode root() const { return {&doc_, ""}; }
  int line_of(const std::string& path) const;  // 0 when unknown

  [[noreturn]] void fail(const JsonNode& at, const std::string& message) const;

  // An object whose keys must all be in `allowed`.
  void expect_object(const JsonNode& n, std::initializer_list<const char*> allowed) const;
  JsonNode required(const JsonNode& object, const std::string& key) const;
  std::vector<JsonNode> elements(const JsonNode& array) const;
  std::vector<JsonNode> elements(const JsonNode& array, size_t count) const;  // exactly count

  // Conversions; `number` also takes integers, `integer` takes no fractions.
  double number(const JsonNode& n) const;
  long integer(const JsonNode& n) const;
  bool boolean(const JsonNode& n) const;
  std::string text(const JsonNode& n) const;

  double number(const JsonNode& object, const std::string& key) const { return number(required(object, key)); }
  long integer(const JsonNode& object, const std::string& key) const { return integer(required(object, key)); }
  bool boolean(const JsonNode& object, const std::string& key) const { return boolean(required(object, key)); }
  std::string text(const JsonNode& object, const std::string& key) const { return text(required(object, key)); }

 private:
  std::string file_;
  nlohmann::json doc_;
  std::map<std::string, int> lines_;  // path -> 1-based line where the value starts
};

}  // namespace rigflex::io
