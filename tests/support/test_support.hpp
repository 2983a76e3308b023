#pragma once
// Helpers shared by the test suites: the verification cases of
// shared/verification (targets read from the YAML files, never copied into
// tests), and small model builders.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "fe/model.hpp"
#include "reduction/modal_analysis.hpp"

namespace rigflex::test {

struct Target {
  int mode = 0;
  double freq_hz = 0.0;
};

std::string verification_path(const std::string& file);
YAML::Node verification_case(const std::string& file);
// The `targets` of a case file, or of its `additional_cases` entry whose
// `case` equals case_name.
std::vector<Target> verification_targets(const std::string& file, const std::string& case_name = "");
std::vector<double> verification_frequencies(const std::string& file, const std::string& case_name = "");

// reduction::run_modal_analysis for the `count` lowest modes, expecting
// converged, accurate and M-orthogonal eigenpairs.
reduction::ModalAnalysis checked_modal_analysis(const fe::Model& m, int count);

// The `count` lowest frequencies (Hz) of the model in a model file's text,
// by checked_modal_analysis; fewer is a failure naming `name`, and gives an
// empty vector.
Eigen::VectorXd model_frequencies(const std::string& text, const std::string& name, int count);
// The frequencies of f past its `rigid` rigid modes: those below 1e-3 Hz and
// the next above `first_elastic_hz`, each a failure otherwise. Empty f
// (a failure already) gives an empty result.
Eigen::VectorXd elastic_modes(const Eigen::VectorXd& f, int rigid, double first_elastic_hz);

}  // namespace rigflex::test
