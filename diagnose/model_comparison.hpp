#pragma once
// `rigflex compare` as a function: every history compared with the model
// (diagnose/history_comparison.hpp), the residuals analysed (diagnose/residual_analysis.hpp), the
// mass properties identified from the same records with the model's
// algorithm (flexible when the model has a flexible frame or rods), and the
// checks that tell a user the model does not fit the data at all. With
// `fit_model`, the body (and each model parameter whose uncertainty the rig
// file states) is refitted with the swing states first, as diagnose's
// baseline (diagnose/baseline_fit.hpp): a user's body is never exact, and its
// error would otherwise show as the model's.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "diagnose/baseline_fit.hpp"
#include "diagnose/history_comparison.hpp"
#include "diagnose/residual_analysis.hpp"
#include "fe/mass_properties.hpp"
#include "identify/identification.hpp"

namespace rigflex::diagnose {

struct ModelComparison {
  std::vector<std::string> channels;
  std::vector<HistoryComparison> histories;
  Eigen::VectorXd nrmse;  // per channel, pooled, swing band (diagnose/history_comparison.hpp)
  double overall_nrmse = 0, force_nrmse = 0, angle_nrmse = 0;
  Eigen::VectorXd raw_nrmse;  // per channel, pooled, every sample
  double raw_overall_nrmse = 0, raw_force_nrmse = 0;
  ResidualAnalysis analysis;
  identify::IdentificationAlgorithm algorithm = identify::IdentificationAlgorithm::rigid;
  std::optional<identify::IdentificationResult> identified;  // empty with identification_error set
  std::string identification_error;
  std::vector<std::string> warnings;  // what to check when the model does not follow the data
  // The model's own parameters refitted (ModelComparisonOptions::fit_model).
  // Where that fit is credible every figure above is the refitted model's,
  // and `as_stated` holds the rig file's model's NRMSEs.
  std::optional<ModelParameterFit> model_fit;
  struct Nrmse {
    double overall = 0, force = 0, angle = 0;
  };
  std::optional<Nrmse> as_stated;
};

struct ModelComparisonOptions {
  CompareOptions compare;
  bool identify = true;
  bool fit_model = false;  // refit the body and the stated-uncertain parameters first
  int threads = 0;
  std::function<void(int done, int total)> progress;
  std::function<void(const std::string&)> fit_progress;  // the model fit's stages
};

// RecordError-free: a record that does not fit the rig throws
// std::invalid_argument naming the source (rod count) or a rig::RecordError from
// the identification's kinematics (an impossible angle), with its history set.
ModelComparison compare_model(const ResponseModel& m, const std::vector<const rig::Record*>& records,
                              const std::vector<std::string>& sources, const ModelComparisonOptions& options);

// The warning thresholds: a model that misses the data's first seconds by
// more than kFollowLimit (overall swing-band NRMSE over the fit window: worse
// than no model of the swing at all) does not follow the data from the start.
constexpr double kFollowLimit = 1.0;

}  // namespace rigflex::diagnose
