#pragma once
// The assembled rig: rigid motion of carrying frame + body (position of P and
// a unit quaternion, so no rotation singularity), elastic modal coordinates
// of the carrying frame about its mean axes, reduced coordinates of the fixed
// frame, rods as axial springs between the joint centres, gravity and the
// effects' loads.
//
// Equations (frame c components for the body, xi = (V, w) the velocity of P
// and the angular velocity, both in frame c, M_b the 6x6 mass matrix about P):
//   M_b xi' = (F - w x p, tau - w x h - V x p),  (p, h) = M_b xi
//   eta'' + D eta' + diag(omega2) eta = sum_i psi_i' R' f_i
//   M_f x'' + C_f x' + K_f x = sum_i E_i g_i
// with f_i the loads at B_i, g_i those at A_i (-F_i u_i and F_i u_i from rod
// i). The body's kinetic energy 1/2 xi' M_b xi has a constant matrix, so the
// undamped equations conserve energy exactly (Kirchhoff's equations); the
// elastic modes are M-orthogonal to the rigid motions (mean axes), so the
// carrying frame's elastic and rigid inertia do not couple.
//
// Rods without the rod_compliance effect are rigid: realized as axial springs
// that put the rods' bounce mode at kRigidRodHz: the stretch under the static
// load is g / (2 pi kRigidRodHz)^2 = 2.8e-6 m (a 1e-6 change of a 1.5 m
// pendulum's length), and the floor that rounding sets on the rod forces,
// k eps |x|, stays near 5e-11 of the weight. The check counts those modes as
// constraints, not as deformation modes.
#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "rig/effect.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::rig {

constexpr double kRigidRodHz = 300.0;

struct Configuration {
  Vec3 r = Vec3::Zero();                               // P in G
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // frame c -> G
  Eigen::VectorXd eta;                                 // carrying-frame modal coordinates
  Eigen::VectorXd xf;                                  // fixed-frame reduced coordinates
};

struct Velocity {
  Vec3 V = Vec3::Zero();  // velocity of P, frame c
  Vec3 w = Vec3::Zero();  // angular velocity, frame c
  Eigen::VectorXd eta, xf;
};

// A load applied from outside (the operator's push): force at the CoG and a
// moment, both in G.
struct ExternalLoad {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

// Strain energy by component, for the design check.
struct StrainEnergy {
  double fixed_frame = 0, rods = 0, carrying_frame = 0;
  double total() const { return fixed_frame + rods + carrying_frame; }
};

class RigSystem {
 public:
  // Validates the model (std::invalid_argument) and lets every effect build.
  explicit RigSystem(const RigModel& model);
  // As above, with stiffness scale factors on the three components (design check).
  RigSystem(const RigModel& model, double scale_fixed, double scale_rods, double scale_carrying);

  const RigModel& model() const { return model_; }
  const RigAssembly& assembly() const { return assembly_; }
  int rods() const { return n_; }
  int elastic_modes() const { return ne_; }
  int fixed_dofs() const { return nf_; }
  int coordinate_count() const { return 6 + ne_ + nf_; }
  int state_size() const { return 13 + 2 * (ne_ + nf_); }
  bool rods_rigid() const { return rods_rigid_; }
  const Eigen::VectorXd& rod_stiffness() const { return k_; }
  const Eigen::VectorXd& rod_damping() const { return c_; }  // N s/m, zeros: none
  const Eigen::Matrix<double, 6, 6>& body_mass() const { return Mb_; }
  double suspended_mass() const { return Mb_(0, 0); }
  Vec3 gravity_vector() const { return Vec3(0, 0, -assembly_.geometry.gravity); }
  // Total weight carried by the rods (N): body and the lower halves of the rods.
  double suspended_weight() const;

  Configuration nominal() const;
  Velocity at_rest() const;
  // Perturbation s = (dr (frame c), dtheta (frame c), d eta, d xf):
  // r + R T(dtheta) dr, R exp(dtheta), eta + d eta, xf + d xf, the
  // exponential of SE(3) for (dr, dtheta) (T: SO(3)'s left Jacobian).
  Configuration displaced(const Configuration& c, const Eigen::VectorXd& s) const;
  void displaced(const Configuration& c, const Eigen::VectorXd& s, Configuration& out) const;  // out != c

  Kinematics kinematics(const Configuration& c, const Velocity& v, double t) const;
  void kinematics(const Configuration& c, const Velocity& v, double t, Kinematics& out) const;
  // Generalized forces (F, tau in frame c; modal; fixed-frame coordinates).
  Eigen::VectorXd generalized_forces(const Configuration& c, const Velocity& v, double t,
                                     const ExternalLoad* external = nullptr) const;
  // The same into Q, with the evaluation's scratch kept in `work` (no
  // allocation once sized: the integrators call this thousands of times).
  struct Workspace {
    Kinematics kinematics;
    Loads loads;
  };
  void generalized_forces(const Configuration& c, const Velocity& v, double t, const ExternalLoad* external,
                          Workspace& work, Eigen::VectorXd& Q) const;
  // Q minus the gyroscopic terms of the body block: the right-hand side of
  // M d(xi, eta', xf')/dt = ... (in place).
  void subtract_gyroscopic(const Velocity& v, Eigen::VectorXd& Q) const;
  // Loads only (no inertia): used by the sensors, which read the rod forces.
  void collect_loads(const Kinematics& k, Loads& loads, const ExternalLoad* external) const;
  // d(xi, eta', xf')/dt from the generalized forces.
  Eigen::VectorXd accelerations(const Velocity& v, const Eigen::VectorXd& Q) const;
  // The mass matrix of the coordinates s at rest (body block in frame c).
  Eigen::MatrixXd mass_matrix() const;

  double kinetic_energy(const Velocity& v) const;
  double potential_energy(const Configuration& c) const;
  StrainEnergy strain_energy(const Configuration& c) const;  // relative to the unstrained state
  // Strain energy of an increment s about c (1/2 s' K_component s, exact for the linear parts).
  StrainEnergy incremental_strain_energy(const Configuration& c, const Eigen::VectorXd& s) const;

  // State vector y = (r - P_nominal, q(w,x,y,z), eta, xf, V, w, eta', xf') for the integrator.
  void pack(const Configuration& c, const Velocity& v, double* y) const;
  void unpack(const double* y, Configuration& c, Velocity& v) const;

 private:
  void build();
  Vec3 joint_displacement_lower(const Eigen::VectorXd& eta, int i) const;

  RigModel model_;
  RigAssembly assembly_;
  int n_ = 0, ne_ = 0, nf_ = 0;
  bool rods_rigid_ = true;
  Eigen::VectorXd k_, c_, L_, rod_mass_;
  Eigen::Matrix<double, 6, 6> Mb_;
  Eigen::LLT<Eigen::Matrix<double, 6, 6>> Mb_llt_;
  Eigen::LLT<Eigen::MatrixXd> Mf_llt_;
  Vec3 cog_c_;  // CoG of the record, frame c
};

}  // namespace rigflex::rig
