#include "diagnose/effect_candidates.hpp"

#include <cmath>

#include "rig/effect_ranges.hpp"
#include "rig/effect_uncertainty.hpp"

namespace rigflex::diagnose {

CandidateContext candidate_context(const rig::RigSystem& rig, double lowest_swing_hz) {
  CandidateContext c;
  c.geometry = rig.assembly().geometry;
  c.rods = rig.rods();
  c.rod_stiffness = rig.assembly().rod_stiffness;
  c.suspended_mass = rig.suspended_mass();
  c.body_mass = rig.assembly().body.mass;
  c.weight_per_rod = rig.suspended_weight() / c.rods;
  c.rod_static_stretch = c.weight_per_rod / rig.rod_stiffness().maxCoeff();
  rig::Vec3 centroid = rig::Vec3::Zero();
  for (const auto& r : c.geometry.rods) {
    c.rod_length += r.length / c.rods;
    centroid += r.lower / c.rods;
  }
  for (const auto& r : c.geometry.rods) c.joint_radius += (r.lower - centroid).squaredNorm() / c.rods;
  c.joint_radius = std::sqrt(c.joint_radius);
  c.swing_omega = 2.0 * 3.141592653589793 * (lowest_swing_hz > 0 ? lowest_swing_hz : 0.5);
  return c;
}

std::vector<EffectCandidate> effect_candidates(const CandidateContext& context) {
  std::vector<EffectCandidate> out;
  for (const rig::EffectKind& kind : rig::effect_kinds()) {
    rig::EffectFitting f = kind.fit(context);
    auto write = f.write;
    // The values go through the rig reader's checks (ranges, then the
    // kind's own): a block it would refuse throws rig::ParameterError
    // instead of becoming a file that compare --effects cannot read.
    auto block = [&kind, write, context](const Eigen::VectorXd& theta, const Eigen::VectorXd& std) {
      rig::ParameterValue v = write(theta);
      const rig::EffectParseContext x = rig::parse_context(context.geometry, context.body_mass, kind.name);
      rig::check_ranges(kind, v, rig::range_scales(x));
      kind.parse(v, x);
      if (std.size() > 0) {
        if (auto u = rig::fitted_uncertainty(kind, write, theta, std)) v.set("uncertainty", std::move(*u));
      }
      return rig::effect_yaml(kind.name, v);
    };
    out.push_back({kind.name, std::move(f.parameters), std::move(f.make), std::move(block), std::move(f.advice),
                   std::move(f.evidence), f.stand_in});
  }
  return out;
}

}  // namespace rigflex::diagnose
