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

// The rigid algorithm's error on a short virtual measurement, and the verdict
// that weighs it with the frequency ratio's.
struct Prediction {
  int sets = 0, histories = 0;
  double duration_s = 0;
  std::optional<ErrorSummary> rigid;             // against the true body; none when not observable
  std::optional<ErrorSummary> from_flexibility;  // rigid - flexible on the same data
  std::optional<ErrorSummary> flexible;          // against the true body
  std::vector<std::string> unobservable;
  std::string note;
  rig::Verdict verdict = rig::Verdict::rigid_safe;   // of the flexibility's error alone
  rig::Verdict combined = rig::Verdict::rigid_safe;  // worse of ratio and that
};

// `check` is the rig's design check (its verdict is the ratio's).
Prediction predict_identification_error(const rig::RigModel& model, const rig::CheckResult& check,
                                        const VirtualStudyOptions& options);

}  // namespace rigflex::identify
