#include "rig/rig_model.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "rig/effect.hpp"

namespace rigflex::rig {
namespace {

void require(bool ok, const std::string& field, const std::string& message) {
  if (!ok) throw std::invalid_argument(field + ": " + message);
}

bool finite(const Vec3& v) { return v.allFinite(); }

// A rod is "far from" its length beyond this fraction: a calibrated rig's
// joint centres and lengths agree to millimetres, so 5 % is a wrong entry,
// not a tolerance of the lab.
constexpr double kReachTolerance = 0.05;

// Joint centres closer than this are one (m): joints are centimetres apart
// at least, and a calibration is good to a millimetre.
constexpr double kDistinctJoints = 1e-3;

}  // namespace

Eigen::Matrix3d inertia_tensor(const std::array<double, 6>& J) {
  Eigen::Matrix3d t;
  t << J[0], J[3], J[4], J[3], J[1], J[5], J[4], J[5], J[2];
  return t;
}

std::array<double, 6> inertia_components(const Eigen::Matrix3d& J) {
  return {J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2)};
}

void RigModel::validate_input() const {
  validate();
  // Two rods on one joint centre carry as one: the body hangs from fewer
  // points than the rig has rods, its yaw and tilt unobservable or
  // unrestrained - a copied line of the calibration, not a rig.
  const int n = geometry.rod_count();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) {
      const RodGeometry &a = geometry.rods[i], &b = geometry.rods[j];
      const std::string at = "geometry.rods[" + std::to_string(i + 1) + "]";
      const std::string other = " as rod " + std::to_string(j + 1) + ": each rod hangs from a joint of its own";
      require((a.upper - b.upper).norm() >= kDistinctJoints, at + ".upper", "the same upper joint centre" + other);
      require((a.lower - b.lower).norm() >= kDistinctJoints, at + ".lower", "the same lower joint centre" + other);
    }
  }
  // A real body's principal moments obey the triangle inequality. Checked on
  // input only: a fit's trial inertia may cross it by a probe (a thin disk
  // lies on it), and the equations of motion hold for any positive definite
  // tensor.
  const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(body.inertia).eigenvalues();
  require(p(0) + p(1) >= p(2) * (1 - 1e-9), "body.inertia",
          "principal moments violate the triangle inequality (no mass distribution has them)");
}

std::array<double, 6> BodyUncertainty::inertia_std(const fe::MassProperties& body) const {
  if (inertia) return *inertia;
  const double s = kDefaultInertiaShare * body.inertia.trace() / 3.0;
  return {s, s, s, s, s, s};
}

void SimulationOptions::validate() const {
  require(relative_tolerance > 0 && relative_tolerance < 1e-2, "simulation.relative_tolerance",
          "must lie in (0, 1e-2)");
  require(position_tolerance > 0, "simulation.position_tolerance", "must be positive");
  require(max_step_s >= 0, "simulation.max_step", "must be >= 0");
  require(max_order >= 1 && max_order <= 5, "simulation.max_order", "must be 1 to 5");
  require(resolve_hz >= 0 && resolve_hz <= 1e5, "simulation.resolve_hz", "must lie in [0, 1e5] Hz");
}

void RigModel::validate() const {
  const int n = geometry.rod_count();
  require(n == 3 || n == 4, "geometry.rods", "a rig has 3 or 4 rods (got " + std::to_string(n) + ")");
  require(std::isfinite(geometry.gravity) && geometry.gravity > 0, "geometry.gravity", "must be positive");
  require(finite(geometry.reference_point), "geometry.reference_point", "must be finite");
  for (int i = 0; i < n; ++i) {
    const RodGeometry& rod = geometry.rods[i];
    const std::string at = "geometry.rods[" + std::to_string(i + 1) + "]";
    require(finite(rod.upper) && finite(rod.lower), at, "joint centres must be finite");
    require(std::isfinite(rod.length) && rod.length > 0, at + ".length", "must be positive");
    require(std::abs(rod.encoder_axis.norm() - 1.0) < 1e-6, at + ".encoder_axis",
            "must be a unit vector (|a| = " + std::to_string(rod.encoder_axis.norm()) + ")");
    require(std::abs(rod.encoder_axis.z()) < 1e-6, at + ".encoder_axis", "must be horizontal (a_z = " +
                                                                           std::to_string(rod.encoder_axis.z()) + ")");
    const double reach = (rod.upper - geometry.reference_point - rod.lower).norm();
    require(std::abs(reach - rod.length) <= kReachTolerance * rod.length, at + ".length",
            "the rod cannot reach: |A - P - B| = " + std::to_string(reach) + " m at the nominal pose, length " +
                std::to_string(rod.length) + " m");
  }
  require(std::isfinite(body.mass) && body.mass > 0, "body.mass", "must be positive");
  require(finite(body.cog), "body.cog", "must be finite");
  require(body.inertia.allFinite(), "body.inertia", "must be finite");
  require((body.inertia - body.inertia.transpose()).norm() == 0.0, "body.inertia",
          "must be symmetric (J_xy = J_yx, J_xz = J_zx, J_yz = J_zy exactly)");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(body.inertia);
  const Eigen::Vector3d p = eig.eigenvalues();
  require(p.minCoeff() > 0, "body.inertia", "the inertia tensor must be positive definite (principal moments " +
                                                std::to_string(p(0)) + ", " + std::to_string(p(1)) + ", " +
                                                std::to_string(p(2)) + ")");
  require(finite(body_uncertainty.cog) && body_uncertainty.cog.minCoeff() >= 0, "body.uncertainty.cog",
          "standard deviations must be finite and >= 0");
  if (body_uncertainty.inertia) {
    for (double x : *body_uncertainty.inertia) {
      require(std::isfinite(x) && x >= 0, "body.uncertainty.inertia", "standard deviations must be finite and >= 0");
    }
  }
  // Empty, or one finite value per rod, positive or (`zero_allowed`) >= 0.
  const auto per_rod = [n](const std::vector<double>& v, const std::string& at, bool zero_allowed) {
    require(v.empty() || static_cast<int>(v.size()) == n, at,
            "needs one value per rod (" + std::to_string(n) + "), got " + std::to_string(v.size()));
    for (double x : v) {
      require(std::isfinite(x) && (zero_allowed ? x >= 0 : x > 0), at,
              zero_allowed ? "must be >= 0" : "must be positive");
    }
  };
  per_rod(rods.stiffness, "rods.stiffness", false);
  per_rod(rods.damping, "rods.damping", true);
  require(std::isfinite(rods.stiffness_uncertainty) && rods.stiffness_uncertainty >= 0 &&
              rods.stiffness_uncertainty < 1,
          "rods.uncertainty.stiffness", "a relative standard deviation: must lie in [0, 1)");
  require(rods.stiffness_uncertainty == 0 || !rods.stiffness.empty(), "rods.uncertainty.stiffness",
          "needs the rods' stiffness (rods.stiffness, or youngs_modulus and area): rigid rods have none to refit");
  require(sensors.sample_rate_hz > 0, "sensors.sample_rate", "must be positive");
  require(sensors.force_noise_n >= 0 && sensors.angle_noise_rad >= 0 && sensors.force_resolution_n >= 0,
          "sensors", "noise and resolution must be >= 0");
  require(sensors.encoder_bits >= 0 && sensors.encoder_bits <= 48, "sensors.encoder.bits", "must lie in [0, 48]");
  require(release.push_duration_s > 0, "release.push_duration", "must be positive");
  require(release.push_acceleration[0] >= 0 && release.push_acceleration[1] >= release.push_acceleration[0],
          "release.push_acceleration", "must be [min, max] with 0 <= min <= max");
  require(release.push_yaw_acceleration >= 0, "release.push_yaw_acceleration", "must be >= 0");
  simulation.validate();
  std::set<std::string> names;
  for (const auto& e : effects) {
    require(e != nullptr, "effects", "null effect");
    require(names.insert(e->name()).second, std::string("effects.") + e->name(), "switched on twice");
    e->validate(n);
  }
}

const Effect* RigModel::effect(const std::string& name) const {
  for (const auto& e : effects) {
    if (name == e->name()) return e.get();
  }
  return nullptr;
}

}  // namespace rigflex::rig
