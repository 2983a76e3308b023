#pragma once
// The rig as the user describes it (rig.yaml): the spec's geometry block, the
// mass properties of what hangs from the rods, sensors, the release protocol
// and the physical effects switched on. Units SI, conventions of
// shared/spec/rig-conventions.md.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fe/mass_properties.hpp"
#include "rig/effect_uncertainty.hpp"

namespace rigflex::rig {

using Vec3 = Eigen::Vector3d;

struct RodGeometry {
  Vec3 upper = Vec3::Zero();         // A_i in G (m)
  Vec3 lower = Vec3::Zero();         // B_i in frame c (m)
  double length = 0.0;               // L_i (m), unloaded
  Vec3 encoder_axis = Vec3::UnitX();  // a_i in G, horizontal unit vector
};

struct RigGeometry {
  double gravity = 9.80665;
  Vec3 reference_point = Vec3::Zero();  // P at the nominal pose, in G
  std::vector<RodGeometry> rods;
  int rod_count() const { return static_cast<int>(rods.size()); }
};

struct SensorOptions {
  double sample_rate_hz = 500.0;
  double force_noise_n = 0.0;       // standard deviation of load-cell noise (N)
  double force_resolution_n = 0.0;  // load-cell quantum (N); 0 = continuous
  int encoder_bits = 0;             // counts per turn 2^bits; 0 = continuous
  double angle_noise_rad = 0.0;     // standard deviation of encoder noise (rad)
};

// Given initial conditions: the operator holds the body displaced along the
// swing coordinates (the other coordinates settle statically) and lets go.
struct InitialCondition {
  double x = 0.0, y = 0.0;  // m, horizontal displacement of P from equilibrium
  double yaw = 0.0;         // rad, about the vertical
  Vec3 velocity = Vec3::Zero();          // m/s of P, in G
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, in G
};

// A human push: a raised-cosine force pulse on the body at its CoG, of random
// horizontal direction and size, plus a random yaw moment, after which the
// free swing is recorded.
struct ReleaseOptions {
  double push_duration_s = 1.0;
  std::array<double, 2> push_acceleration{0.15, 0.45};  // m/s^2: peak force / mass, drawn uniformly
  double push_yaw_acceleration = 0.3;                   // rad/s^2: peak moment / Jzz, drawn in [-a, a]
  std::vector<InitialCondition> initial;                // non-empty: use these instead of pushes
};

// generalized_alpha (default): fixed step from the rig's modes, see
// rig/generalized_alpha.hpp; position_tolerance bounds its Newton
// corrections. bdf: CVODE with error control, order <= max_order (2: BDF2
// is A-stable, so the undamped rod and frame vibrations at 80-900 Hz do not
// limit the step; orders 3-5 are unstable there unless every step resolves
// them). The methods' effect on the signals is measured by
// bench_rig_simulation against a tight BDF run (docs/rig.md).
enum class IntegrationMethod { generalized_alpha, bdf };
struct SimulationOptions {
  IntegrationMethod method = IntegrationMethod::generalized_alpha;
  double relative_tolerance = 1e-6;
  double position_tolerance = 1e-10;  // m (rad for angles), absolute
  double max_step_s = 0.0;           // 0: no limit
  int max_order = 2;                 // 1-5 (bdf)
  // generalized_alpha resolves (>= 30 steps per period) every mode up to
  // this frequency; 0: the swing modes and the first deformation mode.
  double resolve_hz = 0.0;
  void validate() const;              // std::invalid_argument
};

// The rods' own axial properties, what every rig has and its drawings give
// (the rig file's `rods` block): a spring between the joint centres and a
// dashpot beside it. Nominal values, not effects: diagnose refits a rod
// compliance on top of them (rig/effect_kinds_structure.cpp) and the
// rod_compliance effect, where present, replaces the stiffness.
struct RodProperties {
  std::vector<double> stiffness;  // N/m per rod; empty: rigid (rig/rig_system.hpp)
  std::vector<double> damping;    // N s/m per rod, on the rate of stretch; empty: none
  // How well the user knows the stiffness (rods.uncertainty.stiffness): one
  // relative standard deviation for a factor common to every rod (the
  // joints' and load cells' share of the axial compliance is rarely
  // known better than the rods' own). diagnose refits that factor with it
  // as the prior (diagnose/body_parameters.hpp); 0: held as given.
  double stiffness_uncertainty = 0.0;
};

class Effect;

// How well the user knows the body's mass properties, one standard deviation
// per component: the priors of diagnose's fits (diagnose/body_parameters.hpp),
// which refit the CoG and the inertia with every candidate effect. A zero
// holds the component as given. Defaults: what a user typically has - the
// CoG from a static reference measurement (3 mm in plane, 7 mm in height)
// and the inertia from a rigid identification on a rig that is not quite
// rigid (10 % of the mean principal moment, products included).
struct BodyUncertainty {
  Vec3 cog{0.003, 0.003, 0.007};            // m
  std::optional<std::array<double, 6>> inertia;  // kg m^2, Jxx Jyy Jzz Jxy Jxz Jyz; none: the default
  static constexpr double kDefaultInertiaShare = 0.10;
  // The inertia's standard deviations, the default resolved against `body`.
  std::array<double, 6> inertia_std(const fe::MassProperties& body) const;
};

struct RigModel {
  std::string name;
  RigGeometry geometry;
  // Mass properties of what hangs from the rods: carrying frame + body (or
  // the carrying frame alone for a tare), about the CoG, in frame c.
  fe::MassProperties body;
  BodyUncertainty body_uncertainty;
  RodProperties rods;
  SensorOptions sensors;
  ReleaseOptions release;
  SimulationOptions simulation;
  std::vector<std::shared_ptr<const Effect>> effects;
  // The effects whose parameters the rig file states an uncertainty for
  // (`effects.<name>.uncertainty`): diagnose refits them like the body.
  std::vector<EffectUncertainty> effect_uncertainty;

  // Throws std::invalid_argument naming the offending field ("rods[2].encoder_axis").
  void validate() const;
  // validate() and what only a user's input must satisfy besides (the
  // body's principal moments obey the triangle inequality).
  void validate_input() const;
  const Effect* effect(const std::string& name) const;  // nullptr if not switched on
};

// Inertia tensor from the spec's [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] (negative-integral products).
Eigen::Matrix3d inertia_tensor(const std::array<double, 6>& J);
std::array<double, 6> inertia_components(const Eigen::Matrix3d& J);

}  // namespace rigflex::rig
