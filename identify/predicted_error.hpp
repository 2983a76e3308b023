#pragma once
// The design check's second opinion: the rigid algorithm's error predicted
// on a short virtual measurement of the rig.
//
// The frequency ratio alone misses what static deflection does: the joints
// move with the rod loads, and the rigid algorithm misplaces the CoG height
// even at 5.8x. So the check also identifies a virtual measurement
// (identify/virtual_identification.hpp) and judges the rigid algorithm's error
// against the rig's 2-sigma accuracy: |mean| + 2 std of zG and of each
// moment, the largest product and in-plane CoG error inside the limits:
// safe; inside twice the limits: marginal; else use the flexible algorithm.
// Flexibility is blamed only when the flexible algorithm meets the accuracy
// on the same data; otherwise noise and excitation limit the identification
// and the ratio decides.
#include <optional>
#include <string>
#include <vector>

#include "identify/mass_statistics.hpp"
#include "identify/virtual_identification.hpp"
#include "rig/design_check.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::identify {

rig::Verdict predicted_verdict(const ErrorSummary& rigid, const AccuracyLimits& limits = {});
// How far outside the accuracy limits (1 = on the limit), by the worst component.
double accuracy_score(const ErrorSummary& e, const AccuracyLimits& limits = {});

// The rigid algorithm's error on a short virtual measurement of the model,
// and the verdict of that error alone.
struct Prediction {
  int sets = 0, histories = 0;
  double duration_s = 0;
  std::optional<ErrorSummary> rigid;             // against the true body; none when not observable
  std::optional<ErrorSummary> from_flexibility;  // rigid - flexible on the same data
  std::optional<ErrorSummary> flexible;          // against the true body
  std::vector<std::string> unobservable;
  std::string note;
  rig::Verdict verdict = rig::Verdict::rigid_safe;  // of the error alone; conclude_check weighs it with the ratio
};

Prediction predict_identification_error(const rig::RigModel& model, const VirtualStudyOptions& options);

// The one verdict of `rigflex check`: the worse of the frequency ratio's and
// the predicted error's, with which of them decided and why; and the one
// piece of advice, how much stiffer and where, answering the stricter need.
struct CheckConclusion {
  rig::Verdict verdict = rig::Verdict::rigid_safe;
  std::string reason;
  std::optional<rig::StiffnessAdvice> advice;
  std::string advice_reason;  // "frequency ratio" or "predicted error"
};
CheckConclusion conclude_check(const rig::CheckResult& check, const std::optional<Prediction>& prediction,
                               const AccuracyLimits& limits = {});

}  // namespace rigflex::identify
