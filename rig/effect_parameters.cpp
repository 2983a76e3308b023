#include "rig/effect_parameters.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rigflex::rig {
namespace {

std::string number_text(double x) {
  std::ostringstream s;
  s << std::setprecision(6) << x;
  return s.str();
}

bool is_flat(const ParameterValue& v) {
  if (v.kind == ParameterValue::Kind::scalar) return true;
  if (v.kind != ParameterValue::Kind::list) return false;
  for (const auto& x : v.items) {
    if (x.kind != ParameterValue::Kind::scalar) return false;
  }
  return true;
}

// A scalar or a list, on one line.
std::string flow(const ParameterValue& v) {
  if (v.kind == ParameterValue::Kind::scalar) return v.number ? number_text(*v.number) : v.text;
  if (v.kind == ParameterValue::Kind::map) {
    std::string s = "{";
    for (size_t i = 0; i < v.entries.size(); ++i) {
      s += (i ? ", " : "") + v.entries[i].key + ": " + flow(v.entries[i].value);
    }
    return s + "}";
  }
  std::string s = "[";
  for (size_t i = 0; i < v.items.size(); ++i) s += (i ? ", " : "") + flow(v.items[i]);
  return s + "]";
}

// The entries of a map, one per line; nested maps as blocks.
std::string block(const ParameterValue& map, int indent) {
  std::string s;
  for (const auto& e : map.entries) {
    s += std::string(static_cast<size_t>(indent), ' ') + e.key + ":";
    if (e.value.kind == ParameterValue::Kind::map) {
      s += "\n" + block(e.value, indent + 2);
    } else {
      s += " " + flow(e.value) + "\n";
    }
  }
  return s;
}

}  // namespace

const ParameterValue& ParameterValue::operator[](const std::string& key) const {
  static const ParameterValue absent;
  for (const auto& e : entries) {
    if (e.key == key) return e.value;
  }
  return absent;
}

ParameterValue ParameterValue::of(double x) {
  ParameterValue v;
  v.kind = Kind::scalar;
  v.number = x;
  v.text = number_text(x);
  return v;
}

ParameterValue ParameterValue::of(const std::vector<double>& v) {
  std::vector<ParameterValue> items;
  for (double x : v) items.push_back(of(x));
  return list(std::move(items));
}

ParameterValue ParameterValue::of(const Eigen::VectorXd& v) { return of(std::vector<double>(v.data(), v.data() + v.size())); }

ParameterValue ParameterValue::list(std::vector<ParameterValue> items) {
  ParameterValue v;
  v.kind = Kind::list;
  v.items = std::move(items);
  return v;
}

ParameterValue ParameterValue::map() {
  ParameterValue v;
  v.kind = Kind::map;
  return v;
}

ParameterValue& ParameterValue::set(const std::string& key, ParameterValue value) {
  entries.push_back({key, 0, std::move(value)});
  return *this;
}

bool operator==(const ParameterValue& a, const ParameterValue& b) {
  if (a.kind != b.kind || a.items.size() != b.items.size() || a.entries.size() != b.entries.size()) return false;
  if (a.kind == ParameterValue::Kind::scalar && (a.number ? a.number != b.number : a.text != b.text)) return false;
  for (size_t i = 0; i < a.items.size(); ++i) {
    if (!(a.items[i] == b.items[i])) return false;
  }
  for (size_t i = 0; i < a.entries.size(); ++i) {
    if (a.entries[i].key != b.entries[i].key || !(a.entries[i].value == b.entries[i].value)) return false;
  }
  return true;
}

ParameterError::ParameterError(int line, std::string key, const std::string& reason)
    : std::runtime_error(key + ": " + reason), line_(line), key_(std::move(key)), reason_(reason) {}

void ParameterReader::fail(const ParameterValue& at, const std::string& key, const std::string& message) {
  throw ParameterError(at.line, key, message);
}

void ParameterReader::expect_map(const ParameterValue& n, const std::string& what,
                                 const std::vector<std::string>& allowed) {
  if (n.kind != ParameterValue::Kind::map) fail(n, what, "expected a mapping of keys");
  for (const auto& e : n.entries) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || e.key == a;
    if (!ok) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw ParameterError(e.key_line, e.key, "unknown key in " + what + " (allowed: " + list + ")");
    }
  }
}

void ParameterReader::expect_sequence(const ParameterValue& n, const std::string& key) {
  if (n.kind != ParameterValue::Kind::list) fail(n, key, "expected a list");
}

const ParameterValue& ParameterReader::required(const ParameterValue& map, const std::string& key) {
  const ParameterValue& v = map[key];
  if (v.kind == ParameterValue::Kind::absent || v.kind == ParameterValue::Kind::null) {
    fail(map, key, "missing required key");
  }
  return v;
}

double ParameterReader::as_number(const ParameterValue& v, const std::string& key) {
  if (v.kind != ParameterValue::Kind::scalar || !v.number) fail(v, key, "expected a number");
  if (!std::isfinite(*v.number)) fail(v, key, "expected a finite number");
  return *v.number;
}

Eigen::Vector3d ParameterReader::as_vec3(const ParameterValue& v, const std::string& key) {
  if (v.kind != ParameterValue::Kind::list || v.items.size() != 3) {
    fail(v, key, "expected a list of 3 numbers [x, y, z]");
  }
  return {as_number(v.items[0], key), as_number(v.items[1], key), as_number(v.items[2], key)};
}

double ParameterReader::number(const ParameterValue& map, const std::string& key) {
  return as_number(required(map, key), key);
}

double ParameterReader::number_or(const ParameterValue& map, const std::string& key, double fallback) {
  return map[key].defined() ? as_number(map[key], key) : fallback;
}

std::string ParameterReader::text_or(const ParameterValue& map, const std::string& key, const std::string& fallback) {
  if (!map[key].defined()) return fallback;
  const ParameterValue& v = required(map, key);
  if (v.kind != ParameterValue::Kind::scalar) fail(v, key, "expected a string");
  return v.text;
}

Eigen::Vector3d ParameterReader::vec3(const ParameterValue& map, const std::string& key) {
  return as_vec3(required(map, key), key);
}

std::vector<double> ParameterReader::numbers(const ParameterValue& map, const std::string& key, size_t count) {
  const ParameterValue& v = required(map, key);
  if (v.kind != ParameterValue::Kind::list || v.items.size() != count) {
    fail(v, key, "expected a list of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (const auto& e : v.items) out.push_back(as_number(e, key));
  return out;
}

std::vector<double> ParameterReader::per_rod(const ParameterValue& map, const std::string& key, int rods) {
  const ParameterValue& v = required(map, key);
  if (v.kind == ParameterValue::Kind::scalar) return std::vector<double>(static_cast<size_t>(rods), as_number(v, key));
  return numbers(map, key, static_cast<size_t>(rods));
}

std::vector<Eigen::Vector3d> ParameterReader::per_rod_vectors(const ParameterValue& map, const std::string& key,
                                                              int rods) {
  const ParameterValue& v = required(map, key);
  expect_sequence(v, key);
  if (static_cast<int>(v.items.size()) != rods) {
    fail(v, key,
         "needs one [x, y, z] per rod (" + std::to_string(rods) + "), got " + std::to_string(v.items.size()));
  }
  std::vector<Eigen::Vector3d> out;
  for (const auto& e : v.items) out.push_back(as_vec3(e, key));
  return out;
}

std::string effect_yaml(const std::string& name, const ParameterValue& parameters, int indent) {
  const std::string pad(static_cast<size_t>(indent), ' ');
  bool one_line = parameters.kind == ParameterValue::Kind::map;
  for (const auto& e : parameters.entries) one_line = one_line && is_flat(e.value);
  if (one_line) return pad + name + ": " + flow(parameters) + "\n";
  return pad + name + ":\n" + block(parameters, indent + 2);
}

}  // namespace rigflex::rig
