#pragma once
// Physical effects plug into the rig through three hooks, so that a new one
// is a class and an entry of the catalogue's table (rig/effect_kinds.hpp),
// never an edit of the core:
//   build    - structure: geometry truth, rod stiffness and mass, frames;
//   add_loads - forces that depend on the motion (friction, drag);
//   measure  - the measurement chain (offsets, gains).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rig/rig_model.hpp"

namespace rigflex::rig {

// The fixed frame reduced onto the upper joint centres, grounded.
struct FixedFrameModel {
  Eigen::MatrixXd K, M, C;        // reduced coordinates^2
  std::vector<int> joint_row;     // rod i: first of the three rows UX UY UZ of A_i
  std::string source;
};

// The carrying frame reduced onto the lower joint centres, free-free, in
// elastic modal coordinates about its mean axes: joint displacement
// d_i = psi_i eta (frame c), eta'' + damping eta' + diag(omega2) eta = psi' f.
struct CarryingFrameModel {
  Eigen::MatrixXd psi;        // 3n x modes: rows 3i..3i+2 are joint i (frame c)
  Eigen::VectorXd omega2;     // (rad/s)^2 per elastic mode
  Eigen::MatrixXd damping;    // modes x modes, psi' C psi of the reduced C
  std::string source;
};

// What the effects may change before the rig is assembled: the true rig.
struct RigAssembly {
  RigGeometry geometry;                 // truth (geometry errors applied)
  fe::MassProperties body;
  std::vector<double> rod_stiffness;    // N/m; empty: rods rigid (see rig_system.hpp)
  std::vector<double> rod_damping;      // N s/m; empty: none
  std::vector<double> rod_mass;         // kg per rod
  std::optional<FixedFrameModel> fixed_frame;
  std::optional<CarryingFrameModel> carrying_frame;
  double stiffness_scale_fixed = 1.0, stiffness_scale_carrying = 1.0, stiffness_scale_rods = 1.0;
};

// Motion of the rig at one instant, in G unless noted.
struct RodKinematics {
  Vec3 A, B;          // joint centres
  Vec3 vA, vB;        // their velocities
  Vec3 lower_c;       // B_i in frame c, deformation included
  Vec3 u;             // unit vector A -> B
  double length = 0;  // |B - A|
  Vec3 u_rate;        // du/dt
  double force = 0;   // axial force, tension positive (spring)
};

struct Kinematics {
  double t = 0;
  Eigen::Matrix3d R;   // frame c -> G
  Vec3 r;              // P in G
  Vec3 v;              // velocity of P in G
  Vec3 omega;          // angular velocity of the carrying frame in G
  Vec3 cog;            // CoG in G
  std::vector<RodKinematics> rods;
};

// Loads on the rig collected during one evaluation (G components).
struct Loads {
  Vec3 body_force = Vec3::Zero();   // resultant on the hanging body ...
  Vec3 body_moment = Vec3::Zero();  // ... and its moment about P
  std::vector<Vec3> lower_force;    // at B_i on the carrying frame (elastic too)
  std::vector<Vec3> lower_moment;   // couples at B_i on the carrying frame
  std::vector<Vec3> upper_force;    // at A_i on the fixed frame
  void reset(int rods);
  void add_body_force(const Vec3& f, const Vec3& at_minus_P);
};

// One sample of the sensors, before noise and quantization.
struct SensorSample {
  double t = 0;
  Eigen::VectorXd force, alpha, beta;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual const char* name() const = 0;           // the spec's effect name
  virtual void validate(int rods) const = 0;       // std::invalid_argument naming the parameter
  virtual void build(RigAssembly&) const {}
  virtual void add_loads(const Kinematics&, Loads&) const {}
  virtual void measure(SensorSample&) const {}
  // The inverse of measure: what the identifier applies to recorded samples
  // when the rig model knows the measurement chain (calibrated offsets, gains).
  virtual void unmeasure(SensorSample&) const {}
  virtual bool dissipative() const { return false; }
};

}  // namespace rigflex::rig
