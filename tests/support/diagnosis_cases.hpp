#pragma once
// The diagnosis cases of issue 17's acceptance, shared by the tests
// (tests/acceptance: one seed per case) and bench/bench_diagnosis_seeds
// (many seeds): the trifilar of tests/support/rig_cases.hpp (the bench
// also its quadrifilar) with one catalogue effect hidden at a magnitude
// that lifts its swing-band force or angle NRMSE well above the noise's
// floor (so that a 5x fall after adding the fitted effect can be
// measured), its virtual measurement, and the model a user really has of
// it: the CoG from a static reference (drawn within
// +-3, +-3, +-7 mm of the truth), the inertia from rigflex's rigid
// identification of the same records, the rods nominal.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "diagnose/body_parameters.hpp"
#include "diagnose/diagnosis.hpp"
#include "identify/identification.hpp"
#include "identify/identification_rig.hpp"
#include "io/effects_file.hpp"
#include "io/rig_reader.hpp"
#include "rig/effects.hpp"
#include "rig/joint_compliance.hpp"
#include "rig/simulation.hpp"

namespace rigflex::test {

constexpr int kHiddenEffects = 10;

// The frames' stand-ins hidden in a case (the sway is the same on every rig).
inline std::shared_ptr<const rig::Effect> hidden_fixed_frame(const rig::RigModel& start,
                                                             std::vector<rig::Vec3> joints) {
  rig::FixedJointCompliance c;
  c.joints = std::move(joints);
  c.sway = Eigen::Vector2d(3e-6, 1.5e-6);
  return std::make_shared<rig::FixedFrameFlexibility>(
      rig::joint_compliance_fixed_frame(start.geometry, start.body.mass, c));
}

inline std::shared_ptr<const rig::Effect> hidden_carrying_frame(const rig::RigModel& start) {
  rig::CarryingJointCompliance c;
  c.translation = rig::Vec3(3e-6, 2e-6, 1e-6);
  c.rocking = Eigen::Vector2d(4e-6, 2e-6);
  return std::make_shared<rig::CarryingFrameFlexibility>(
      rig::joint_compliance_carrying_frame(start.geometry, start.body.mass, c));
}

// The effect `which` on a four-rod rig (noisy_quadrifilar in
// tests/support/rig_cases.hpp: 613 N per rod, rods of 2e7 N/m): the
// trifilar's magnitudes with a fourth joint, rod or cell, except where the
// rods' stated stiffness changes what a size means. A rod length error
// there is a self-stress: 0.02 mm on one rod shifts the rods' forces at
// rest by some 100 N (the trifilar's millimetres would be kilonewtons). The
// upper joints are off sideways only, as on tests/diagnose/
// test_four_rod_fit.cpp (a joint's height is a rod length error there).
// Rod compliance is not among them: the rods' stiffness is part of this
// model, so rods softer than stated are a model parameter off, not a
// missing effect.
inline std::shared_ptr<const rig::Effect> four_rod_hidden_effect(int which, const rig::RigModel& start) {
  switch (which) {
    case 0:
      return hidden_fixed_frame(start, {rig::Vec3(3e-6, 9e-6, 1.5e-6), rig::Vec3(6e-6, 3e-6, 1.5e-6),
                                        rig::Vec3(3e-6, 6e-6, 3e-6), rig::Vec3(6e-6, 6e-6, 2e-6)});
    case 1:
      return hidden_carrying_frame(start);
    case 2:
      return nullptr;
    case 3:
      return std::make_shared<rig::RodMass>(std::vector<double>{3.0, 3.0, 3.0, 3.0});
    case 4: {
      rig::JointFrictionParameters f;
      f.viscous = 0.3;
      f.coulomb = 0.05;
      return std::make_shared<rig::JointFriction>(f);
    }
    case 5:
      return std::make_shared<rig::AirDrag>(rig::AirDragParameters{1.2, 10.0, 30.0, std::nullopt});
    case 6:
      return std::make_shared<rig::EncoderOffset>(std::vector<double>{0.002, -0.001, 0.0, 0.001},
                                                  std::vector<double>{0.0, 0.001, -0.002, 0.0005});
    case 7:
      return std::make_shared<rig::RodLengthError>(std::vector<double>{2e-5, 0.0, 0.0, 0.0});
    case 8:
      return std::make_shared<rig::JointPositionError>(
          std::vector<rig::Vec3>{rig::Vec3(0.003, 0, 0), rig::Vec3(0, -0.003, 0), rig::Vec3(0.002, 0.002, 0),
                                 rig::Vec3::Zero()},
          std::vector<rig::Vec3>(4, rig::Vec3::Zero()));
    default:
      return std::make_shared<rig::LoadCellGain>(std::vector<double>{1.01, 0.99, 1.02, 1.0},
                                                 std::vector<double>{5.0, 0.0, -5.0, 2.0});
  }
}

// The catalogue's effect `which` hidden in `start`'s rig: the trifilar's
// (noisy_trifilar) below, a four-rod rig's above; nullptr where the rig
// has no such case. Throws std::invalid_argument for another rod count.
inline std::shared_ptr<const rig::Effect> hidden_effect(int which, const rig::RigModel& start) {
  if (start.geometry.rod_count() == 4) return four_rod_hidden_effect(which, start);
  if (start.geometry.rod_count() != 3) throw std::invalid_argument("diagnosis cases: a rig of 3 or 4 rods");
  switch (which) {
    case 0:  // 2-6 mm sideways and 1-2 mm down under a rod's 654 N
      return hidden_fixed_frame(
          start, {rig::Vec3(3e-6, 9e-6, 1.5e-6), rig::Vec3(6e-6, 3e-6, 1.5e-6), rig::Vec3(3e-6, 6e-6, 3e-6)});
    case 1:
      return hidden_carrying_frame(start);
    case 2:  // 2.6 mm stretch under 654 N: a long wire rope
      return std::make_shared<rig::RodCompliance>(std::vector<double>{2.5e5, 2.5e5, 2.5e5});
    case 3: return std::make_shared<rig::RodMass>(std::vector<double>{3.0, 3.0, 3.0});
    case 4: {
      rig::JointFrictionParameters f;
      f.viscous = 0.3;
      f.coulomb = 0.05;
      return std::make_shared<rig::JointFriction>(f);
    }
    case 5:  // a light, bulky body: 10 m^2 of drag area on 200 kg
      return std::make_shared<rig::AirDrag>(rig::AirDragParameters{1.2, 10.0, 30.0, std::nullopt});
    case 6:
      return std::make_shared<rig::EncoderOffset>(std::vector<double>{0.002, -0.001, 0.0},
                                                  std::vector<double>{0.0, 0.001, -0.002});
    case 7: return std::make_shared<rig::RodLengthError>(std::vector<double>{0.003, -0.002, 0.0});
    case 8:
      return std::make_shared<rig::JointPositionError>(
          std::vector<rig::Vec3>{rig::Vec3(0.003, 0, 0), rig::Vec3(0, -0.003, 0.001), rig::Vec3(0.002, 0.002, 0)},
          std::vector<rig::Vec3>(3, rig::Vec3::Zero()));
    default:
      return std::make_shared<rig::LoadCellGain>(std::vector<double>{1.01, 0.99, 1.02},
                                                 std::vector<double>{5.0, 0.0, -5.0});
  }
}

// The catalogue's effect of that name at the magnitude above; nullptr for none.
inline std::shared_ptr<const rig::Effect> hidden_effect(const std::string& name, const rig::RigModel& start) {
  for (int k = 0; k < kHiddenEffects; ++k) {
    auto e = hidden_effect(k, start);
    if (e && name == e->name()) return e;
  }
  return nullptr;
}

// The effects hidden in a case: a catalogue kind's name (above), "none",
// "below_noise" (air drag on 1/1000 of the hidden case's area with 1/400 of
// its rotational drag: 1/3 of a drag that left 0.5-5 x the noise in excess
// over seeds - the pushes' size sets it - so about 0.05-0.6 x by the
// residual's square law: below the noise, nothing may be named) or "two_effects" (a rod
// length error and load-cell gains at once). Throws std::invalid_argument
// for another name.
inline std::vector<std::shared_ptr<const rig::Effect>> case_effects(const std::string& name,
                                                                    const rig::RigModel& nominal) {
  if (name == "none") return {};
  if (name == "below_noise")
    return {std::make_shared<rig::AirDrag>(rig::AirDragParameters{1.2, 0.01, 0.07, std::nullopt})};
  if (name == "two_effects") return {hidden_effect(7, nominal), hidden_effect(9, nominal)};
  auto e = hidden_effect(name, nominal);
  if (!e) throw std::invalid_argument("no diagnosis case " + name);
  return {e};
}

// The rig the records of a case come from: `nominal` with the case's
// effects. The clean control's records are simulated by CVODE's BDF, not
// by the generalized-alpha integrator every model prediction uses, as
// independently generated data would be: a model error of the integrator
// must not look like a missing effect.
inline rig::RigModel case_truth(const std::string& name, const rig::RigModel& nominal) {
  rig::RigModel truth = nominal;
  for (auto& e : case_effects(name, nominal)) truth.effects.push_back(e);
  if (name == "none") truth.simulation.method = rig::IntegrationMethod::bdf;
  return truth;
}

// The seed tests/acceptance/test_uncertain_body.cpp runs a case with.
inline std::uint64_t acceptance_seed(const std::string& name) { return 700 + std::hash<std::string>{}(name) % 100; }

// The fitted parameter of that name (a body property: "cog_z", ...);
// throws std::invalid_argument where the fit has none.
inline const diagnose::FittedParameter& named(const std::vector<diagnose::FittedParameter>& ps,
                                              const std::string& name) {
  for (const auto& p : ps) {
    if (p.name == name) return p;
  }
  throw std::invalid_argument("no fitted parameter " + name);
}

inline bool control_case(const std::string& name) { return name == "none" || name == "below_noise"; }

// Noise of standard deviation `sigma` through a first-order low-pass at
// `corner_hz` (an amplifier's bandwidth), added to every sample of `x`:
// AR(1), e_k = a e_(k-1) + sqrt(1 - a^2) sigma w_k with a = exp(-2 pi
// corner h), started stationary - its RMS is sigma, its spectral density in
// the swing band (1 + a) / (1 - a) x white noise's of that RMS.
inline void add_coloured_noise(Eigen::MatrixXd& x, double sigma, double corner_hz, double step_s,
                               std::mt19937_64& rng) {
  std::normal_distribution<double> w(0.0, 1.0);
  const double a = std::exp(-2.0 * 3.141592653589793 * corner_hz * step_s), b = std::sqrt(1.0 - a * a);
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    double e = sigma * w(rng);
    for (Eigen::Index k = 0; k < x.rows(); ++k) {
      x(k, c) += e;
      e = a * e + b * sigma * w(rng);
    }
  }
}

// One set of `histories` histories of 15 s (random pushes, the rig file's
// sensor noise; with noise_corner_hz > 0 that noise through a first-order
// low-pass at that corner, its RMS as the rig file states it).
inline std::vector<rig::Record> measure_histories(const rig::RigModel& truth, std::uint64_t seed,
                                                  double noise_corner_hz = 0, int histories = 6) {
  rig::MeasurementOptions o;
  o.histories = histories;
  o.seed = seed;
  if (!(noise_corner_hz > 0)) return rig::simulate_measurement(rig::RigSystem(truth), o).front();
  rig::RigModel clean = truth;
  clean.sensors.force_noise_n = 0;
  clean.sensors.angle_noise_rad = 0;
  std::vector<rig::Record> r = rig::simulate_measurement(rig::RigSystem(clean), o).front();
  std::mt19937_64 rng(seed ^ 0x5eedc0105edULL);
  for (rig::Record& x : r) {
    const double h = 1.0 / x.sample_rate_hz;
    add_coloured_noise(x.force, truth.sensors.force_noise_n, noise_corner_hz, h, rng);
    add_coloured_noise(x.alpha, truth.sensors.angle_noise_rad, noise_corner_hz, h, rng);
    add_coloured_noise(x.beta, truth.sensors.angle_noise_rad, noise_corner_hz, h, rng);
  }
  return r;
}

inline std::vector<const rig::Record*> record_pointers(const std::vector<rig::Record>& r) {
  std::vector<const rig::Record*> p;
  for (const auto& x : r) p.push_back(&x);
  return p;
}

// The user's model of `nominal`: the CoG off by a draw within the static
// reference's accuracy, the inertia as the rigid identification gives it
// from the records - or, where the records do not determine it (the
// identification says which moments it cannot observe), a CAD estimate:
// the principal moments off by a draw within +-10 %.
inline rig::RigModel users_model(const rig::RigModel& nominal, const std::vector<rig::Record>& data,
                                 std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  rig::RigModel m = nominal;
  m.body.cog += rig::Vec3(0.003 * u(rng), 0.003 * u(rng), 0.007 * u(rng));
  const identify::IdentificationRig idr =
      identify::identification_rig(nominal, identify::IdentificationAlgorithm::rigid);
  const identify::IdentificationResult r = identify::identify(idr, record_pointers(data), {});
  if (r.observable) {
    m.body.inertia = r.properties.inertia;
  } else {
    const Eigen::Vector3d scale(1.0 + 0.1 * u(rng), 1.0 + 0.1 * u(rng), 1.0 + 0.1 * u(rng));
    const Eigen::Matrix3d J = scale.cwiseSqrt().asDiagonal() * nominal.body.inertia * scale.cwiseSqrt().asDiagonal();
    m.body.inertia = 0.5 * (J + J.transpose());  // d_i J_ij d_j and d_j J_ji d_i round apart
  }
  return m;
}

// `start` with what diagnose found added as a user adds it: the body's
// (and a refitted rod stiffness's) offsets where they are reported (`body_credible`), and the
// effects' rig block written as an effects file and read back through the
// reader.
inline rig::RigModel with_found(const rig::RigModel& start, const std::vector<diagnose::FittedParameter>& body,
                                bool body_credible, const std::string& rig_block, const std::string& label) {
  rig::RigModel m = start;
  if (body_credible && !body.empty()) {
    const diagnose::BodyParameters bp = diagnose::body_parameters(start);
    Eigen::VectorXd delta(bp.size());
    for (int k = 0; k < bp.size(); ++k) delta(k) = body[static_cast<size_t>(k)].value;
    m = diagnose::model_with(start, bp, delta);
  }
  if (!rig_block.empty()) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() / ("rigflex-found-" + label + ".yaml");
    {
      std::ofstream out(file);
      out << io::effects_file_text({}, rig_block);
    }
    io::add_effects(m, file);
    std::filesystem::remove(file);
  }
  return m;
}

// One effect as the ranking fitted it.
inline rig::RigModel with_found(const rig::RigModel& start, const diagnose::EffectFit& found) {
  return with_found(start, found.body, found.body_credible, found.rig_block, found.effect);
}

// Every effect of the diagnosis' chain as its last step refitted them; the
// first-ranked effect where nothing was found.
inline rig::RigModel with_found(const rig::RigModel& start, const diagnose::Diagnosis& d) {
  if (d.chain.empty()) return with_found(start, d.ranking.front());
  const diagnose::ChainStep& last = d.chain.back();
  return with_found(start, last.body, last.body_credible, last.rig_block, "chain-" + last.effect);
}

}  // namespace rigflex::test
