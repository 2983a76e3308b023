#pragma once
// Small rigs with closed-form answers, shared by the rig tests.
#include <cmath>
#include <numbers>

#include "rig/effect_kinds.hpp"
#include "rig/effect_ranges.hpp"
#include "rig/linearization.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::test {

// n equal vertical rods of length L at radius R around P (upper joints above
// the lower ones), carrying a uniform disk of mass m and radius Rd whose CoG
// lies `drop` below the joint plane; g = 9.81 as in
// shared/verification/pendulum_closed_form.yaml.
inline rig::RigModel multifilar_rig(int n = 3, double R = 0.4, double L = 1.0, double m = 100.0, double Rd = 0.5,
                                    double drop = 0.0) {
  rig::RigModel model;
  model.name = "multifilar";
  model.geometry.gravity = 9.81;
  model.geometry.reference_point = rig::Vec3(0, 0, 0);
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / n + 0.3;
    rig::RodGeometry rod;
    rod.lower = rig::Vec3(R * std::cos(phi), R * std::sin(phi), 0.0);
    rod.upper = rod.lower + rig::Vec3(0, 0, L);
    rod.length = L;
    rod.encoder_axis = rig::Vec3(std::cos(phi), std::sin(phi), 0.0);
    model.geometry.rods.push_back(rod);
  }
  model.body.mass = m;
  model.body.cog = rig::Vec3(0, 0, -drop);
  model.body.inertia = Eigen::Vector3d(m * Rd * Rd / 4, m * Rd * Rd / 4, m * Rd * Rd / 2).asDiagonal();
  return model;
}

// The trifilar of the compare and diagnose tests: 200 kg on three 1 m rods
// at 0.5 m, CoG off centre, load cells with 1 N and encoders with 2e-5 rad
// of noise at 500 Hz.
inline rig::RigModel noisy_trifilar() {
  rig::RigModel m = multifilar_rig(3, 0.5, 1.0, 200.0, 0.6, 0.2);
  m.body.cog = rig::Vec3(0.05, -0.03, -0.2);
  m.sensors.sample_rate_hz = 500;
  m.sensors.force_noise_n = 1.0;
  m.sensors.angle_noise_rad = 2e-5;
  return m;
}

// A quadrifilar: 250 kg on four vertical 1.2 m rods of 2e7 N/m at the
// corners of a 1.1 x 0.84 m rectangle, the CoG off centre, the spec's
// sensor noise. Four rods on a rigid carrying frame are statically
// indeterminate: the rods' axial stiffness is part of the nominal model.
inline rig::RigModel noisy_quadrifilar() {
  rig::RigModel m = multifilar_rig(4, 0.6, 1.2, 250.0, 0.7, 0.25);
  const double corner[4][2] = {{0.55, 0.42}, {-0.55, 0.42}, {-0.55, -0.42}, {0.55, -0.42}};
  for (int i = 0; i < 4; ++i) {
    rig::RodGeometry& rod = m.geometry.rods[i];
    rod.lower = rig::Vec3(corner[i][0], corner[i][1], 0.0);
    rod.upper = rod.lower + rig::Vec3(0, 0, 1.2);
    rod.encoder_axis = rig::Vec3(1, 0, 0);
  }
  m.body.cog = rig::Vec3(0.03, 0.02, -0.25);
  m.body.inertia << 22, 0.4, -0.8, 0.4, 30, 0.3, -0.8, 0.3, 40;
  m.rods.stiffness.assign(4, 2e7);
  m.sensors.sample_rate_hz = 500;
  m.sensors.force_noise_n = 1.0;
  m.sensors.angle_noise_rad = 2e-5;
  return m;
}

// The effect `name` with these parameters added to `m` as a rig file's
// `effects:` block adds it (io/rig_reader.cpp): its `uncertainty`, if any,
// to m.effect_uncertainty, the rest parsed by the effect's kind.
inline void add_effect(rig::RigModel& m, const std::string& name, rig::ParameterValue parameters) {
  const rig::EffectKind& kind = *rig::find_effect_kind(name);
  const rig::EffectParseContext x = rig::parse_context(m, name);
  const rig::RangeScales scales = rig::range_scales(x);
  if (auto u = rig::take_uncertainty(kind, parameters, m.geometry.rod_count(), scales)) {
    m.effect_uncertainty.push_back(std::move(*u));
  }
  rig::check_ranges(kind, parameters, scales);
  m.effects.push_back(kind.parse(parameters, x));
}

// The swing mode in which coordinate j (of s) moves most, by kinetic energy share.
inline double swing_frequency_along(const rig::Linearization& lin, int j) {
  double best = -1, f = 0;
  for (const auto& m : lin.modes) {
    if (m.kind != rig::RigModeKind::swing) continue;
    const double share = m.shape(j) * (lin.M * m.shape)(j);
    if (share > best) best = share, f = m.frequency_hz;
  }
  return f;
}

}  // namespace rigflex::test
