#include "support/test_support.hpp"

#include <stdexcept>

namespace rigflex::test {

std::string verification_path(const std::string& file) { return std::string(RIGFLEX_VERIFICATION_DIR) + "/" + file; }

YAML::Node verification_case(const std::string& file) { return YAML::LoadFile(verification_path(file)); }

std::vector<Target> verification_targets(const std::string& file, const std::string& case_name) {
  const YAML::Node root = verification_case(file);
  YAML::Node targets;
  if (case_name.empty()) {
    targets = root["targets"];
  } else {
    for (const auto& c : root["additional_cases"])
      if (c["case"].as<std::string>() == case_name) targets = c["targets"];
  }
  if (!targets.IsDefined() || !targets.IsSequence())
    throw std::runtime_error("no targets for case '" + case_name + "' in " + file);
  std::vector<Target> out;
  for (const auto& t : targets) out.push_back({t["mode"].as<int>(), t["freq_hz"].as<double>()});
  return out;
}

std::vector<double> verification_frequencies(const std::string& file, const std::string& case_name) {
  std::vector<double> f;
  for (const Target& t : verification_targets(file, case_name)) f.push_back(t.freq_hz);
  return f;
}

}  // namespace rigflex::test
