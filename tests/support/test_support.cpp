#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "io/model_reader.hpp"

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

reduction::ModalAnalysis checked_modal_analysis(const fe::Model& m, int count) {
  linalg::EigenOptions opt;
  opt.count = count;
  auto a = reduction::run_modal_analysis(m, opt);
  EXPECT_TRUE(a.result.converged) << a.result.message;
  // Backward error: the pair is exact for K, M perturbed by this much
  // (relative). The Lanczos accepts a Ritz pair at the default tolerance
  // 1e-10 on the transformed problem, which bounds it at that level. The
  // plain ratio ||Kx - lMx|| / ||Kx|| is not usable here: K x of a rigid-body
  // mode is rounding noise, and the portal frame's K has a condition ~1e8.
  EXPECT_LT(a.result.backward_errors.maxCoeff(), 1e-10);
  EXPECT_LT(a.result.orthogonality_error, 1e-10);
  return a;
}

Eigen::VectorXd model_frequencies(const std::string& text, const std::string& name, int count) {
  const io::ModelFile file = io::parse_model(text, name);
  const Eigen::VectorXd f = checked_modal_analysis(file.model, count).result.frequencies_hz();
  if (f.size() >= count) return f;
  ADD_FAILURE() << name << ": " << f.size() << " of " << count << " modes";
  return {};
}

Eigen::VectorXd elastic_modes(const Eigen::VectorXd& f, int rigid, double first_elastic_hz) {
  if (f.size() <= rigid) return {};
  EXPECT_LT(f(rigid - 1), 1e-3) << rigid << " rigid modes expected";
  EXPECT_GT(f(rigid), first_elastic_hz) << "only " << rigid << " rigid modes expected";
  return f.tail(f.size() - rigid);
}

}  // namespace rigflex::test
