#include "identify/sweep.hpp"

#include <atomic>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "identify/identification_rig.hpp"
#include "rig/equilibrium.hpp"
#include "rig/linearization.hpp"
#include "rig/parallel_for.hpp"
#include "rig/simulation.hpp"

namespace rigflex::identify {

std::vector<double> ScaleRange::values() const {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) {
    const double f = count == 1 ? 0.0 : static_cast<double>(i) / (count - 1);
    v.push_back(start * std::pow(stop / start, f));
  }
  return v;
}

void ScaleRange::validate(const std::string& name) const {
  if (!(start > 0) || !(stop > 0) || !std::isfinite(start) || !std::isfinite(stop)) {
    throw std::invalid_argument(name + ": scales must be positive (start:stop:count)");
  }
  if (count < 1 || count > 1000) throw std::invalid_argument(name + ": count must be 1..1000");
}

void SweepOptions::validate() const {
  mass.validate("--mass-scale");
  stiffness.validate("--stiffness-scale");
  study.validate();
  // Every point simulates a whole measurement: bounded like one.
  const double records = static_cast<double>(mass.count + stiffness.count) * study.sets * study.histories;
  if (records > rig::kMaxHistories) {
    throw std::invalid_argument("the sweep would simulate " + std::to_string(static_cast<long long>(records)) +
                                " records (points x sets x histories); at most " +
                                std::to_string(static_cast<long>(rig::kMaxHistories)) + " in one run");
  }
}

const char* to_string(SweepKind k) { return k == SweepKind::mass ? "mass" : "stiffness"; }

namespace {

SweepPoint evaluate(const rig::RigModel& nominal, SweepKind kind, double scale, const VirtualStudyOptions& study) {
  SweepPoint p;
  p.kind = kind;
  p.scale = scale;
  rig::RigModel model = nominal;
  StiffnessScale stiff;
  if (kind == SweepKind::mass) {
    model.body.mass *= scale;
    model.body.inertia *= scale;
  } else {
    stiff = {scale, scale, scale};
  }
  try {
    const rig::RigSystem truth(model, stiff.fixed_frame, stiff.rods, stiff.carrying_frame);
    const rig::Linearization lin = linearize(truth);
    double swing = 0;
    for (const rig::RigMode& m : lin.modes) {
      if (m.kind == rig::RigModeKind::swing) swing = std::max(swing, m.frequency_hz);
      if (m.kind == rig::RigModeKind::deformation && !p.f1_hz) p.f1_hz = m.frequency_hz;
    }
    p.swing_max_hz = swing;
    if (p.f1_hz && swing > 0) p.ratio = *p.f1_hz / swing;
    const IdentificationRig rigid = identification_rig(model, IdentificationAlgorithm::rigid, stiff);
    const IdentificationRig flexible = identification_rig(model, IdentificationAlgorithm::flexible, stiff);
    VirtualStudyOptions o = study;
    o.progress = nullptr;
    const VirtualStudy s = virtual_identification(truth, &rigid, &flexible, o);
    for (const auto& [outcome, summary] : {std::pair{&s.rigid, &p.rigid}, {&s.flexible, &p.flexible}}) {
      if ((*outcome)->observable) {
        *summary = summarize_errors((*outcome)->found, s.truth);
      } else if (p.failure.empty()) {
        p.failure = (*outcome)->message;
      }
    }
  } catch (const rig::NoEquilibrium& e) {
    p.failure = std::string("no static equilibrium: ") + e.what();
  } catch (const std::exception& e) {
    // A point the model cannot carry (a mass matrix that is no longer
    // positive, records no pose fits) is a result of the sweep, not its end.
    p.failure = e.what();
  }
  return p;
}

}  // namespace

std::vector<SweepPoint> sweep(const rig::RigModel& model, const SweepOptions& options) {
  options.validate();
  std::vector<std::pair<SweepKind, double>> points;
  for (double s : options.mass.values()) points.emplace_back(SweepKind::mass, s);
  for (double s : options.stiffness.values()) points.emplace_back(SweepKind::stiffness, s);
  std::vector<SweepPoint> out(points.size());
  std::mutex m;
  int done = 0;
  const int total = static_cast<int>(points.size());
  rig::parallel_for(total, options.threads, [&](int i) {
    out[static_cast<size_t>(i)] = evaluate(model, points[static_cast<size_t>(i)].first,
                                           points[static_cast<size_t>(i)].second, options.study);
    if (options.progress) {
      std::lock_guard<std::mutex> lock(m);
      options.progress(++done, total);
    }
  });
  return out;
}

}  // namespace rigflex::identify
