#pragma once
// Identification of mass properties from free swings (docs/identification.md).
// At each equation time the Newton-Euler equations of the system hanging
// from the rods, written at P in frame c, are linear in
//   x = [xG, yG, zG, Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]   (J about P),
// with m known from static weighing, a the acceleration of P, w and dw the
// angular velocity and acceleration, g the gravity vector (all frame c), F
// and M_P the rods' resultant and its moment about P:
//   m (dw x c + w x (w x c))          = F + m (g - a)
//   J dw + w x (J w) + m c x (a - g)   = M_P
// Stacked over the samples of all histories of a set they form A x = B,
// solved in the least-squares sense (QR, then the pseudo-inverse through the
// SVD of the triangular factor); the inertia is then moved from P to the CoG.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fe/mass_properties.hpp"
#include "identify/identification_kinematics.hpp"
#include "identify/savitzky_golay.hpp"

namespace rigflex::identify {

// Which CoG components come from the static procedure instead of the swing.
enum class CogConstraint { none, in_plane, full };  // 9, 7 or 6 unknowns

struct IdentificationOptions {
  SavitzkyGolayOptions differentiation;
  double equation_rate_hz = 50.0;  // equation times per second of record (the kernels overlap, see the docs)
  CogConstraint cog_constraint = CogConstraint::none;
  rig::Vec3 imposed_cog = rig::Vec3::Zero();  // m, frame c, of the record (the components the constraint fixes)
  // A direction of the unknowns whose standard deviation exceeds this share
  // of its physical scale (rig size for the CoG, m x size^2 for inertia) is
  // not observable from the data.
  double observability_limit = 0.1;
  void validate() const;  // std::invalid_argument naming the option
};

// The kinematics the equations need at one equation time, in frame c.
struct EquationSample {
  Eigen::Matrix3d R;  // frame c -> G
  rig::Vec3 a, w, dw;      // acceleration of P, angular velocity, angular acceleration
  rig::Vec3 force, moment; // rods' resultant on the system and its moment about P
  double pose_residual = 0;  // m, rms distance of the smoothed joints from the fitted rigid pose
};

struct IdentificationResult {
  bool observable = false;
  std::vector<std::string> unobservable;  // the parameters the data cannot fix
  std::string message;
  fe::MassProperties properties;           // of the record, inertia about the CoG
  Eigen::Matrix3d inertia_about_P = Eigen::Matrix3d::Zero();
  Eigen::Vector3d principal_moments = Eigen::Vector3d::Zero();  // ascending
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity(); // columns, frame c
  bool positive_definite = false;
  bool triangle_inequality = false;
  double condition_number = 0;             // of A, columns in physical scales
  Eigen::VectorXd singular_values;         // of A in those scales
  std::array<double, 9> standard_deviation{};  // least-squares estimate per parameter (rows taken as independent)
  double force_residual_rms = 0;           // N
  double moment_residual_rms = 0;          // N m
  double pose_residual_rms = 0;            // m, the point fit over the equation times
  double pose_residual_max = 0;            // m
  int equations = 0;                       // equation times used
};

// The equation times of one history: the joint centres and the loads
// smoothed by one Savitzky-Golay fit, the joints also differentiated twice;
// at each equation time the pose is fitted to the smoothed joints (Kabsch)
// and the rigid velocity and acceleration fields v + w x rho_i and
// a + dw x rho_i + w x (w x rho_i) to their derivatives (least squares over
// the joints). Equation times: every sample whose window lies inside a
// stretch of uniform sampling (a step more than half a sample off the
// median, as a dropped sample makes, splits the record), thinned to
// equation_rate_hz. rig::RecordError when the joints fit no rigid pose.
std::vector<EquationSample> equation_samples(const IdentificationRig& rig, const MotionSeries& motion,
                                             const IdentificationOptions& options);

// Least squares over the equation samples of a set. `mass` of the record,
// `point_masses` the rods' moving thirds (kg at b_i, frame c) that move with
// the system and are taken out of the result.
IdentificationResult solve_mass_properties(const std::vector<EquationSample>& samples, double mass,
                                           const std::vector<std::pair<double, rig::Vec3>>& point_masses, double gravity,
                                           double size, const IdentificationOptions& options);

// One set: every history through motion_series and equation_samples, one least-squares solve.
IdentificationResult identify(const IdentificationRig& rig, const std::vector<const rig::Record*>& histories,
                              const IdentificationOptions& options);

// The body alone: the tare (carrying frame measured alone) taken out of the system.
fe::MassProperties subtract_tare(const fe::MassProperties& system, const fe::MassProperties& tare);

// Inertia about P from inertia about the CoG and back (parallel axes, tensor convention of the spec).
Eigen::Matrix3d inertia_about(const fe::MassProperties& p, const rig::Vec3& point);

}  // namespace rigflex::identify
