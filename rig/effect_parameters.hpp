#pragma once
// Effect parameters as a rig file gives them, without the file format: a
// small tree of maps, lists and scalars, each with its line in the file.
// The effect catalogue (rig/effect_kinds.hpp) reads effects from it and
// writes fitted effects to it; io/ converts YAML to it, so that rig/ needs
// neither yaml-cpp nor io/. ParameterReader is io::YamlContext's strictness
// on this tree: its errors carry the same line, key and reason.
#include <Eigen/Core>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rigflex::rig {

struct ParameterEntry;

struct ParameterValue {
  enum class Kind { absent, null, scalar, list, map };
  Kind kind = Kind::absent;
  int line = 0;                         // 1-based; 0 unknown (absent, or built in memory)
  std::string text;                     // a scalar as written
  std::optional<double> number;         // a scalar that reads as a number by the file format's rule
  std::vector<ParameterValue> items;    // a list
  std::vector<ParameterEntry> entries;  // a map, in the file's order

  bool defined() const { return kind != Kind::absent; }
  // The entry's value, or an absent value (line 0) when the map has none.
  const ParameterValue& operator[](const std::string& key) const;

  // Values built in memory (the writer's side): numbers keep their double.
  static ParameterValue of(double x);
  static ParameterValue of(const std::vector<double>& v);
  static ParameterValue of(const Eigen::VectorXd& v);
  static ParameterValue list(std::vector<ParameterValue> items);
  static ParameterValue map();
  ParameterValue& set(const std::string& key, ParameterValue value);  // appends; returns *this
};

struct ParameterEntry {
  std::string key;
  int key_line = 0;
  ParameterValue value;
};

bool operator==(const ParameterValue& a, const ParameterValue& b);  // structure, text and numbers; not lines

// A parameter the catalogue cannot use: the line and the key (relative to
// the effect, or a full path) of io::InputError, without the file's name.
class ParameterError : public std::runtime_error {
 public:
  ParameterError(int line, std::string key, const std::string& reason);
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  int line_;
  std::string key_, reason_;
};

// Strict reads of a parameter tree, message for message as io::YamlContext.
class ParameterReader {
 public:
  [[noreturn]] static void fail(const ParameterValue& at, const std::string& key, const std::string& message);
  // A map whose keys must all be in `allowed`.
  static void expect_map(const ParameterValue& n, const std::string& what, const std::vector<std::string>& allowed);
  static void expect_sequence(const ParameterValue& n, const std::string& key);

  static const ParameterValue& required(const ParameterValue& map, const std::string& key);
  static double number(const ParameterValue& map, const std::string& key);
  static double number_or(const ParameterValue& map, const std::string& key, double fallback);
  static std::string text_or(const ParameterValue& map, const std::string& key, const std::string& fallback);
  static Eigen::Vector3d vec3(const ParameterValue& map, const std::string& key);
  static std::vector<double> numbers(const ParameterValue& map, const std::string& key, size_t count);
  static double as_number(const ParameterValue& v, const std::string& key);
  static Eigen::Vector3d as_vec3(const ParameterValue& v, const std::string& key);

  // Runs `read` with the keys of its errors named under `path` ("joints"
  // becomes "effects.x.joint_compliance.joints"); keys already under it pass.
  template <class F>
  static auto within(const std::string& path, F read) -> decltype(read()) {
    try {
      return read();
    } catch (const ParameterError& e) {
      const std::string& k = e.key();
      const bool named = k == path || k.rfind(path + ".", 0) == 0 || k.rfind(path + "[", 0) == 0;
      if (k.empty() || named) throw;
      throw ParameterError(e.line(), path + "." + k, e.reason());
    }
  }

  // Per-rod values: a list of `rods`, or one value for all rods.
  static std::vector<double> per_rod(const ParameterValue& map, const std::string& key, int rods);
  // Per-rod [x, y, z]: a list of `rods` of them.
  static std::vector<Eigen::Vector3d> per_rod_vectors(const ParameterValue& map, const std::string& key, int rods);
};

// The YAML block that states effect `name` with these parameters, as it
// stands under `effects:` (indented by `indent` spaces). Numbers with 6
// significant digits; lists in flow style; an effect whose parameters are
// all numbers or lists on one line ("rod_mass: {mass: 2}"), else a block
// with nested maps as blocks. The one writer of effect YAML: diagnose's
// rig_block and the effects files it writes both come from it.
std::string effect_yaml(const std::string& name, const ParameterValue& parameters, int indent = 0);

}  // namespace rigflex::rig
