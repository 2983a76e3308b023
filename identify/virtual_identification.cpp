#include "identify/virtual_identification.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "identify/mass_statistics.hpp"
#include "rig/simulation.hpp"

namespace rigflex::identify {
namespace {

std::optional<VirtualOutcome> identify_sets(const IdentificationRig* rig,
                                            const std::vector<std::vector<rig::Record>>& sets,
                                            const VirtualStudyOptions& o) {
  if (!rig) return std::nullopt;
  VirtualOutcome out;
  for (const auto& set : sets) {
    std::vector<const rig::Record*> ptrs;
    for (const auto& h : set) ptrs.push_back(&h);
    const IdentificationResult r = identify(*rig, ptrs, o.identification);
    if (!r.observable) {
      out.observable = false;
      out.unobservable = r.unobservable;
      out.message = r.message;
      out.found.clear();
      return out;
    }
    out.found.push_back(r.properties);
  }
  return out;
}

}  // namespace

void VirtualStudyOptions::validate() const {
  if (sets < 1 || histories < 1) throw std::invalid_argument("virtual identification: sets and histories must be >= 1");
  if (!(duration_s > 0)) throw std::invalid_argument("virtual identification: duration must be positive");
  rig::MeasurementOptions m;
  m.sets = sets;
  m.histories = histories;
  m.duration_s = duration_s;
  m.validate();
  identification.validate();
}

VirtualStudy virtual_identification(const rig::RigSystem& truth, const IdentificationRig* rigid,
                                    const IdentificationRig* flexible, const VirtualStudyOptions& options) {
  options.validate();
  rig::MeasurementOptions m;
  m.sets = options.sets;
  m.histories = options.histories;
  m.duration_s = options.duration_s;
  m.seed = options.seed;
  m.progress = options.progress;
  const auto sets = simulate_measurement(truth, m);
  VirtualStudy s;
  s.truth = truth.model().body;
  s.rigid = identify_sets(rigid, sets, options);
  s.flexible = identify_sets(flexible, sets, options);
  return s;
}

ErrorSummary summarize_errors(const std::vector<fe::MassProperties>& found,
                              const std::vector<fe::MassProperties>& reference) {
  if (found.empty() || found.size() != reference.size()) {
    throw std::invalid_argument("summarize_errors: needs one reference per identified set");
  }
  ErrorSummary e;
  e.sets = static_cast<int>(found.size());
  std::vector<double> zg;
  std::array<std::vector<double>, 3> moments;
  for (size_t k = 0; k < found.size(); ++k) {
    const fe::MassProperties& p = found[k];
    const fe::MassProperties& t = reference[k];
    const double largest = t.inertia.diagonal().maxCoeff();
    zg.push_back(p.cog.z() - t.cog.z());
    for (int i = 0; i < 3; ++i) moments[static_cast<size_t>(i)].push_back(p.inertia(i, i) / t.inertia(i, i) - 1.0);
    for (auto [i, j] : {std::pair{0, 1}, {0, 2}, {1, 2}}) {
      e.product_max = std::max(e.product_max, std::abs(p.inertia(i, j) - t.inertia(i, j)) / largest);
    }
    e.cog_in_plane_max_m =
        std::max({e.cog_in_plane_max_m, std::abs(p.cog.x() - t.cog.x()), std::abs(p.cog.y() - t.cog.y())});
  }
  const SampleSummary z = summarize(zg);
  e.zG_mean_m = z.mean;
  e.zG_std_m = z.std.value_or(0.0);
  for (size_t i = 0; i < 3; ++i) {
    const SampleSummary m = summarize(moments[i]);
    e.moment_mean[i] = m.mean;
    e.moment_std[i] = m.std.value_or(0.0);
  }
  return e;
}

ErrorSummary summarize_errors(const std::vector<fe::MassProperties>& found, const fe::MassProperties& reference) {
  return summarize_errors(found, std::vector<fe::MassProperties>(found.size(), reference));
}

}  // namespace rigflex::identify
