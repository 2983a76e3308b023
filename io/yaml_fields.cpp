#include "io/yaml_fields.hpp"

#include <cmath>

namespace rigflex::io {

void YamlContext::fail(const YAML::Node& at, const std::string& key, const std::string& message) const {
  throw InputError(file_, at.IsDefined() ? line_of(at) : 0, key, message);
}

void YamlContext::expect_map(const YAML::Node& n, const std::string& what,
                             std::initializer_list<const char*> allowed) const {
  if (!n.IsMap()) fail(n, what, "expected a mapping of keys");
  for (const auto& kv : n) {
    const std::string k = kv.first.as<std::string>();
    bool ok = false;
    for (const char* a : allowed) ok = ok || k == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      throw InputError(file_, line_of(kv.first), k, "unknown key in " + what + " (allowed: " + list + ")");
    }
  }
}

void YamlContext::expect_sequence(const YAML::Node& n, const std::string& key) const {
  if (!n.IsSequence()) fail(n, key, "expected a list");
}

YAML::Node YamlContext::required(const YAML::Node& map, const std::string& key) const {
  const YAML::Node v = map[key];
  if (!v.IsDefined() || v.IsNull()) fail(map, key, "missing required key");
  return v;
}

double YamlContext::as_number(const YAML::Node& v, const std::string& key) const {
  double x = 0.0;
  if (!v.IsScalar() || !YAML::convert<double>::decode(v, x)) fail(v, key, "expected a number");
  if (!std::isfinite(x)) fail(v, key, "expected a finite number");
  return x;
}

long YamlContext::as_integer(const YAML::Node& v, const std::string& key) const {
  long x = 0;
  if (!v.IsScalar() || !YAML::convert<long>::decode(v, x)) fail(v, key, "expected an integer");
  return x;
}

Eigen::Vector3d YamlContext::as_vec3(const YAML::Node& v, const std::string& key) const {
  if (!v.IsSequence() || v.size() != 3) fail(v, key, "expected a list of 3 numbers [x, y, z]");
  return {as_number(v[0], key), as_number(v[1], key), as_number(v[2], key)};
}

int YamlContext::as_count(const YAML::Node& v, const std::string& key, long max) const {
  const long x = as_integer(v, key);
  if (x < 1) fail(v, key, "expected a count of at least 1, got " + std::to_string(x));
  if (x > max) {
    fail(v, key,
         std::to_string(x) + " is more than the " + std::to_string(max) +
             " allowed: a finer mesh than any rig frame needs, and more than a machine can solve");
  }
  return static_cast<int>(x);
}

double YamlContext::number(const YAML::Node& map, const std::string& key) const {
  return as_number(required(map, key), key);
}

double YamlContext::number_or(const YAML::Node& map, const std::string& key, double fallback) const {
  return map[key].IsDefined() ? as_number(map[key], key) : fallback;
}

std::optional<double> YamlContext::optional_number(const YAML::Node& map, const std::string& key) const {
  if (!map[key].IsDefined()) return std::nullopt;
  return as_number(map[key], key);
}

long YamlContext::integer(const YAML::Node& map, const std::string& key) const {
  return as_integer(required(map, key), key);
}

int YamlContext::integer_or(const YAML::Node& map, const std::string& key, int fallback) const {
  return map[key].IsDefined() ? static_cast<int>(as_integer(map[key], key)) : fallback;
}

bool YamlContext::boolean_or(const YAML::Node& map, const std::string& key, bool fallback) const {
  const YAML::Node v = map[key];
  if (!v.IsDefined()) return fallback;
  bool b = false;
  if (!v.IsScalar() || !YAML::convert<bool>::decode(v, b)) fail(v, key, "expected true or false");
  return b;
}

std::string YamlContext::text(const YAML::Node& map, const std::string& key) const {
  const YAML::Node v = required(map, key);
  if (!v.IsScalar()) fail(v, key, "expected a string");
  return v.as<std::string>();
}

std::string YamlContext::text_or(const YAML::Node& map, const std::string& key, const std::string& fallback) const {
  return map[key].IsDefined() ? text(map, key) : fallback;
}

Eigen::Vector3d YamlContext::vec3(const YAML::Node& map, const std::string& key) const {
  return as_vec3(required(map, key), key);
}

std::vector<double> YamlContext::numbers(const YAML::Node& map, const std::string& key, size_t count) const {
  const YAML::Node v = required(map, key);
  if (!v.IsSequence() || v.size() != count) fail(v, key, "expected a list of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (const auto& e : v) out.push_back(as_number(e, key));
  return out;
}

double YamlContext::as_number(const YAML::Node& v, const std::string& key, const PhysicalRange& r) const {
  const double x = as_number(v, key);
  if (const std::string why = range_problem(x, r); !why.empty()) fail(v, key, why);
  return x;
}

Eigen::Vector3d YamlContext::as_vec3(const YAML::Node& v, const std::string& key, const PhysicalRange& r) const {
  const Eigen::Vector3d x = as_vec3(v, key);
  for (int i = 0; i < 3; ++i) as_number(v[i], key, r);
  return x;
}

double YamlContext::number(const YAML::Node& map, const std::string& key, const PhysicalRange& r) const {
  return as_number(required(map, key), key, r);
}

double YamlContext::number_or(const YAML::Node& map, const std::string& key, double fallback,
                              const PhysicalRange& r) const {
  return map[key].IsDefined() ? as_number(map[key], key, r) : fallback;
}

Eigen::Vector3d YamlContext::vec3(const YAML::Node& map, const std::string& key, const PhysicalRange& r) const {
  return as_vec3(required(map, key), key, r);
}

std::vector<double> YamlContext::numbers(const YAML::Node& map, const std::string& key, size_t count,
                                         const PhysicalRange& r) const {
  const std::vector<double> out = numbers(map, key, count);
  for (size_t i = 0; i < count; ++i) as_number(map[key][i], key, r);
  return out;
}

}  // namespace rigflex::io
