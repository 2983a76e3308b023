#pragma once
// Strict access to YAML mappings: every read names the file, line and key
// when the value is missing, of the wrong type, or unknown.
#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/physical_range.hpp"

namespace rigflex::io {

class YamlContext {
 public:
  explicit YamlContext(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& message) const;
  static int line_of(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

  // A mapping whose keys must all be in `allowed`.
  void expect_map(const YAML::Node& n, const std::string& what, std::initializer_list<const char*> allowed) const;
  void expect_sequence(const YAML::Node& n, const std::string& key) const;

  YAML::Node required(const YAML::Node& map, const std::string& key) const;
  double number(const YAML::Node& map, const std::string& key) const;
  double number_or(const YAML::Node& map, const std::string& key, double fallback) const;
  std::optional<double> optional_number(const YAML::Node& map, const std::string& key) const;
  long integer(const YAML::Node& map, const std::string& key) const;
  int integer_or(const YAML::Node& map, const std::string& key, int fallback) const;
  bool boolean_or(const YAML::Node& map, const std::string& key, bool fallback) const;
  std::string text(const YAML::Node& map, const std::string& key) const;
  std::string text_or(const YAML::Node& map, const std::string& key, const std::string& fallback) const;
  Eigen::Vector3d vec3(const YAML::Node& map, const std::string& key) const;
  std::vector<double> numbers(const YAML::Node& map, const std::string& key, size_t count) const;
  // The same, each value also checked against its physical range.
  double number(const YAML::Node& map, const std::string& key, const PhysicalRange& r) const;
  double number_or(const YAML::Node& map, const std::string& key, double fallback, const PhysicalRange& r) const;
  Eigen::Vector3d vec3(const YAML::Node& map, const std::string& key, const PhysicalRange& r) const;
  std::vector<double> numbers(const YAML::Node& map, const std::string& key, size_t count,
                              const PhysicalRange& r) const;

  // Conversions of a value node (not a mapping entry); `key` names it in errors.
  double as_number(const YAML::Node& v, const std::string& key) const;
  long as_integer(const YAML::Node& v, const std::string& key) const;
  // An integer from 1 to `max` (a mesher's division count): checked before
  // it is narrowed to int, so 4294967297 is refused, not meshed as 1.
  int as_count(const YAML::Node& v, const std::string& key, long max) const;
  Eigen::Vector3d as_vec3(const YAML::Node& v, const std::string& key) const;
  double as_number(const YAML::Node& v, const std::string& key, const PhysicalRange& r) const;
  Eigen::Vector3d as_vec3(const YAML::Node& v, const std::string& key, const PhysicalRange& r) const;

 private:
  std::string file_;
};

}  // namespace rigflex::io
