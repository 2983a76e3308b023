#include "rig/skew.hpp"
#include "rig/rig_system.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rigflex::rig {
namespace {

Eigen::Quaterniond exp_map(const Vec3& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle));
}

}  // namespace

void Loads::reset(int rods) {
  body_force.setZero();
  body_moment.setZero();
  lower_force.assign(rods, Vec3::Zero());
  lower_moment.assign(rods, Vec3::Zero());
  upper_force.assign(rods, Vec3::Zero());
}

void Loads::add_body_force(const Vec3& f, const Vec3& at_minus_P) {
  body_force += f;
  body_moment += at_minus_P.cross(f);
}

RigSystem::RigSystem(const RigModel& model) : RigSystem(model, 1.0, 1.0, 1.0) {}

RigSystem::RigSystem(const RigModel& model, double scale_fixed, double scale_rods, double scale_carrying)
    : model_(model) {
  model_.validate();
  if (!(scale_fixed > 0 && scale_rods > 0 && scale_carrying > 0)) {
    throw std::invalid_argument("RigSystem: stiffness scale factors must be positive");
  }
  assembly_.geometry = model_.geometry;
  assembly_.body = model_.body;
  n_ = model_.geometry.rod_count();
  assembly_.rod_mass.assign(n_, 0.0);
  assembly_.rod_stiffness = model_.rods.stiffness;
  assembly_.rod_damping = model_.rods.damping;
  assembly_.stiffness_scale_fixed = scale_fixed;
  assembly_.stiffness_scale_rods = scale_rods;
  assembly_.stiffness_scale_carrying = scale_carrying;
  for (const auto& e : model_.effects) e->build(assembly_);
  build();
}

void RigSystem::build() {
  const RigAssembly& a = assembly_;
  const RigGeometry& g = a.geometry;
  L_.resize(n_);
  rod_mass_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    L_(i) = g.rods[i].length;
    rod_mass_(i) = a.rod_mass[i];
  }
  cog_c_ = a.body.cog;

  // Body mass matrix about P: the record plus a third of each rod's mass at
  // its lower joint (a uniform rod swinging about its upper end has the
  // kinetic energy of m/3 at the lower end).
  double m = a.body.mass;
  Vec3 S = a.body.mass * a.body.cog;
  Eigen::Matrix3d J = a.body.inertia + a.body.mass * (a.body.cog.squaredNorm() * Eigen::Matrix3d::Identity() -
                                                      a.body.cog * a.body.cog.transpose());
  for (int i = 0; i < n_; ++i) {
    const double mi = rod_mass_(i) / 3.0;
    const Vec3& b = g.rods[i].lower;
    m += mi;
    S += mi * b;
    J += mi * (b.squaredNorm() * Eigen::Matrix3d::Identity() - b * b.transpose());
  }
  Mb_.setZero();
  Mb_.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  Mb_.topRightCorner<3, 3>() = -skew(S);
  Mb_.bottomLeftCorner<3, 3>() = skew(S);
  Mb_.bottomRightCorner<3, 3>() = J;
  Mb_llt_.compute(Mb_);
  if (Mb_llt_.info() != Eigen::Success) throw std::invalid_argument("body: mass matrix is not positive definite");

  rods_rigid_ = a.rod_stiffness.empty();
  k_.resize(n_);
  c_ = Eigen::VectorXd::Zero(n_);
  for (int i = 0; i < n_; ++i) {
    if (!a.rod_damping.empty()) c_(i) = a.rod_damping[i];
    if (rods_rigid_) {
      const double w = 2.0 * std::numbers::pi * kRigidRodHz;
      k_(i) = m * w * w / n_;
    } else {
      k_(i) = a.rod_stiffness[i] * a.stiffness_scale_rods;
    }
  }

  ne_ = a.carrying_frame ? static_cast<int>(a.carrying_frame->omega2.size()) : 0;
  nf_ = a.fixed_frame ? static_cast<int>(a.fixed_frame->K.rows()) : 0;
  if (a.fixed_frame) {
    // A third of each rod's mass moves with its upper joint.
    for (int i = 0; i < n_; ++i) {
      for (int d = 0; d < 3; ++d) {
        assembly_.fixed_frame->M(a.fixed_frame->joint_row[i] + d, a.fixed_frame->joint_row[i] + d) +=
            rod_mass_(i) / 3.0;
      }
    }
    assembly_.fixed_frame->K *= a.stiffness_scale_fixed;
    Mf_llt_.compute(assembly_.fixed_frame->M);
    if (Mf_llt_.info() != Eigen::Success) {
      throw std::invalid_argument("fixed_frame_flexibility: reduced mass matrix is not positive definite");
    }
  }
  if (a.carrying_frame) assembly_.carrying_frame->omega2 *= a.stiffness_scale_carrying;
}

double RigSystem::suspended_weight() const {
  return (assembly_.body.mass + 0.5 * rod_mass_.sum()) * assembly_.geometry.gravity;
}

Configuration RigSystem::nominal() const {
  Configuration c;
  c.r = assembly_.geometry.reference_point;
  c.eta = Eigen::VectorXd::Zero(ne_);
  c.xf = Eigen::VectorXd::Zero(nf_);
  return c;
}

Velocity RigSystem::at_rest() const {
  Velocity v;
  v.eta = Eigen::VectorXd::Zero(ne_);
  v.xf = Eigen::VectorXd::Zero(nf_);
  return v;
}

// The left Jacobian of SO(3), T(theta) = I + (1 - cos t)/t^2 [theta] +
// (t - sin t)/t^3 [theta]^2: with it (dr, dtheta) is SE(3)'s exponential, the
// exact motion under a constant body twist (r' = R V, R' = R [w]), which the
// generalized-alpha steps need for second-order accuracy.
namespace {
Eigen::Matrix3d left_jacobian(const Vec3& theta) {
  const double t2 = theta.squaredNorm();
  const Eigen::Matrix3d S = skew(theta);
  double a, b;
  if (t2 < 1e-8) {
    a = 0.5 - t2 / 24.0;
    b = 1.0 / 6.0 - t2 / 120.0;
  } else {
    const double t = std::sqrt(t2);
    a = (1.0 - std::cos(t)) / t2;
    b = (t - std::sin(t)) / (t2 * t);
  }
  return Eigen::Matrix3d::Identity() + a * S + b * S * S;
}
}  // namespace

Configuration RigSystem::displaced(const Configuration& c, const Eigen::VectorXd& s) const {
  Configuration out;
  displaced(c, s, out);
  return out;
}

void RigSystem::displaced(const Configuration& c, const Eigen::VectorXd& s, Configuration& out) const {
  out.r = c.r + c.q * Vec3(left_jacobian(s.segment<3>(3)) * s.segment<3>(0));
  out.q = (c.q * exp_map(s.segment<3>(3))).normalized();
  out.eta = c.eta;
  out.xf = c.xf;
  if (ne_) out.eta += s.segment(6, ne_);
  if (nf_) out.xf += s.segment(6 + ne_, nf_);
}

Vec3 RigSystem::joint_displacement_lower(const Eigen::VectorXd& eta, int i) const {
  if (!ne_) return Vec3::Zero();
  return assembly_.carrying_frame->psi.middleRows<3>(3 * i) * eta;
}

Kinematics RigSystem::kinematics(const Configuration& c, const Velocity& v, double t) const {
  Kinematics k;
  kinematics(c, v, t, k);
  return k;
}

void RigSystem::kinematics(const Configuration& c, const Velocity& v, double t, Kinematics& k) const {
  k.t = t;
  k.R = c.q.normalized().toRotationMatrix();
  k.r = c.r;
  k.v = k.R * v.V;
  k.omega = k.R * v.w;
  k.cog = c.r + k.R * cog_c_;
  k.rods.resize(n_);
  const RigGeometry& g = assembly_.geometry;
  for (int i = 0; i < n_; ++i) {
    RodKinematics& rk = k.rods[i];
    rk.lower_c = g.rods[i].lower + joint_displacement_lower(c.eta, i);
    Vec3 elastic_rate = ne_ ? Vec3(assembly_.carrying_frame->psi.middleRows<3>(3 * i) * v.eta) : Vec3::Zero();
    rk.B = c.r + k.R * rk.lower_c;
    rk.vB = k.R * (v.V + v.w.cross(rk.lower_c) + elastic_rate);
    rk.A = g.rods[i].upper;
    rk.vA.setZero();
    if (nf_) {
      const int row = assembly_.fixed_frame->joint_row[i];
      rk.A += c.xf.segment<3>(row);
      rk.vA = v.xf.segment<3>(row);
    }
    const Vec3 d = rk.B - rk.A;
    rk.length = d.norm();
    rk.u = d / rk.length;
    const Vec3 dv = rk.vB - rk.vA;
    rk.u_rate = (dv - rk.u * rk.u.dot(dv)) / rk.length;
    rk.force = k_(i) * (rk.length - L_(i)) + c_(i) * rk.u.dot(dv);
  }
}

void RigSystem::collect_loads(const Kinematics& k, Loads& loads, const ExternalLoad* external) const {
  loads.reset(n_);
  const Vec3 gvec = gravity_vector();
  loads.add_body_force(assembly_.body.mass * gvec, k.cog - k.r);
  for (int i = 0; i < n_; ++i) {
    const RodKinematics& rk = k.rods[i];
    loads.lower_force[i] += -rk.force * rk.u + 0.5 * rod_mass_(i) * gvec;
    loads.upper_force[i] += rk.force * rk.u;
  }
  if (external) {
    loads.add_body_force(external->force, k.cog - k.r);
    loads.body_moment += external->moment;
  }
  for (const auto& e : model_.effects) e->add_loads(k, loads);
}

Eigen::VectorXd RigSystem::generalized_forces(const Configuration& c, const Velocity& v, double t,
                                              const ExternalLoad* external) const {
  Workspace work;
  Eigen::VectorXd Q;
  generalized_forces(c, v, t, external, work, Q);
  return Q;
}

void RigSystem::generalized_forces(const Configuration& c, const Velocity& v, double t, const ExternalLoad* external,
                                   Workspace& work, Eigen::VectorXd& Q) const {
  const Kinematics& k = work.kinematics;
  kinematics(c, v, t, work.kinematics);
  Loads& loads = work.loads;
  collect_loads(k, loads, external);
  Q.setZero(coordinate_count());
  const Eigen::Matrix3d Rt = k.R.transpose();
  Vec3 F = Rt * loads.body_force;
  Vec3 tau = Rt * loads.body_moment;
  for (int i = 0; i < n_; ++i) {
    const Vec3 fc = Rt * loads.lower_force[i];
    F += fc;
    tau += k.rods[i].lower_c.cross(fc) + Rt * loads.lower_moment[i];
    if (ne_) Q.segment(6, ne_) += assembly_.carrying_frame->psi.middleRows<3>(3 * i).transpose() * fc;
    if (nf_) Q.segment<3>(6 + ne_ + assembly_.fixed_frame->joint_row[i]) += loads.upper_force[i];
  }
  Q.segment<3>(0) = F;
  Q.segment<3>(3) = tau;
  if (ne_) {
    const CarryingFrameModel& cf = *assembly_.carrying_frame;
    Q.segment(6, ne_) -= cf.omega2.cwiseProduct(c.eta) + cf.damping * v.eta;
  }
  if (nf_) {
    const FixedFrameModel& ff = *assembly_.fixed_frame;
    Q.segment(6 + ne_, nf_) -= ff.K * c.xf + ff.C * v.xf;
  }
}

void RigSystem::subtract_gyroscopic(const Velocity& v, Eigen::VectorXd& Q) const {
  Eigen::Matrix<double, 6, 1> xi;
  xi << v.V, v.w;
  const Eigen::Matrix<double, 6, 1> ph = Mb_ * xi;
  const Vec3 p = ph.head<3>(), h = ph.tail<3>();
  Q.segment<3>(0) -= v.w.cross(p);
  Q.segment<3>(3) -= v.w.cross(h) + v.V.cross(p);
}

Eigen::VectorXd RigSystem::accelerations(const Velocity& v, const Eigen::VectorXd& Q) const {
  Eigen::VectorXd rhs = Q;
  subtract_gyroscopic(v, rhs);
  Eigen::VectorXd a(coordinate_count());
  a.head<6>() = Mb_llt_.solve(rhs.head<6>());
  if (ne_) a.segment(6, ne_) = rhs.segment(6, ne_);
  if (nf_) a.segment(6 + ne_, nf_) = Mf_llt_.solve(rhs.segment(6 + ne_, nf_));
  return a;
}

Eigen::MatrixXd RigSystem::mass_matrix() const {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(coordinate_count(), coordinate_count());
  M.topLeftCorner<6, 6>() = Mb_;
  if (ne_) M.block(6, 6, ne_, ne_).setIdentity();
  if (nf_) M.block(6 + ne_, 6 + ne_, nf_, nf_) = assembly_.fixed_frame->M;
  return M;
}

double RigSystem::kinetic_energy(const Velocity& v) const {
  Eigen::Matrix<double, 6, 1> xi;
  xi << v.V, v.w;
  double T = 0.5 * xi.dot(Mb_ * xi);
  if (ne_) T += 0.5 * v.eta.squaredNorm();
  if (nf_) T += 0.5 * v.xf.dot(assembly_.fixed_frame->M * v.xf);
  return T;
}

StrainEnergy RigSystem::strain_energy(const Configuration& c) const {
  StrainEnergy e;
  const Kinematics k = kinematics(c, at_rest(), 0.0);
  for (int i = 0; i < n_; ++i) e.rods += 0.5 * k_(i) * std::pow(k.rods[i].length - L_(i), 2);
  if (ne_) e.carrying_frame = 0.5 * c.eta.dot(assembly_.carrying_frame->omega2.cwiseProduct(c.eta));
  if (nf_) e.fixed_frame = 0.5 * c.xf.dot(assembly_.fixed_frame->K * c.xf);
  return e;
}

StrainEnergy RigSystem::incremental_strain_energy(const Configuration& c, const Eigen::VectorXd& s) const {
  // Rods: the axial stretch rate u . (dB - dA) of the increment; frames: the
  // quadratic forms of their (linear) stiffness.
  StrainEnergy e;
  const Kinematics k = kinematics(c, at_rest(), 0.0);
  Velocity dv = at_rest();
  dv.V = s.segment<3>(0);
  dv.w = s.segment<3>(3);
  if (ne_) dv.eta = s.segment(6, ne_);
  if (nf_) dv.xf = s.segment(6 + ne_, nf_);
  const Kinematics dk = kinematics(c, dv, 0.0);  // velocities = linear increments of positions
  for (int i = 0; i < n_; ++i) {
    const double stretch = k.rods[i].u.dot(dk.rods[i].vB - dk.rods[i].vA);
    e.rods += 0.5 * k_(i) * stretch * stretch;
  }
  if (ne_) e.carrying_frame = 0.5 * dv.eta.dot(assembly_.carrying_frame->omega2.cwiseProduct(dv.eta));
  if (nf_) e.fixed_frame = 0.5 * dv.xf.dot(assembly_.fixed_frame->K * dv.xf);
  return e;
}

double RigSystem::potential_energy(const Configuration& c) const {
  const Kinematics k = kinematics(c, at_rest(), 0.0);
  const Vec3 gvec = gravity_vector();
  double V = strain_energy(c).total() - assembly_.body.mass * gvec.dot(k.cog);
  for (int i = 0; i < n_; ++i) V -= 0.5 * rod_mass_(i) * gvec.dot(k.rods[i].B);
  return V;
}

void RigSystem::pack(const Configuration& c, const Velocity& v, double* y) const {
  int o = 0;
  // P relative to its nominal position: the integrator's relative tolerance
  // then scales with the motion (centimetres), not with the height of P.
  const Vec3 r = c.r - assembly_.geometry.reference_point;
  for (int d = 0; d < 3; ++d) y[o++] = r(d);
  y[o++] = c.q.w();
  y[o++] = c.q.x();
  y[o++] = c.q.y();
  y[o++] = c.q.z();
  for (int j = 0; j < ne_; ++j) y[o++] = c.eta(j);
  for (int j = 0; j < nf_; ++j) y[o++] = c.xf(j);
  for (int d = 0; d < 3; ++d) y[o++] = v.V(d);
  for (int d = 0; d < 3; ++d) y[o++] = v.w(d);
  for (int j = 0; j < ne_; ++j) y[o++] = v.eta(j);
  for (int j = 0; j < nf_; ++j) y[o++] = v.xf(j);
}

void RigSystem::unpack(const double* y, Configuration& c, Velocity& v) const {
  int o = 0;
  c.r = Vec3(y[0], y[1], y[2]) + assembly_.geometry.reference_point;
  o = 3;
  c.q = Eigen::Quaterniond(y[o], y[o + 1], y[o + 2], y[o + 3]);
  o += 4;
  c.eta = Eigen::Map<const Eigen::VectorXd>(y + o, ne_);
  o += ne_;
  c.xf = Eigen::Map<const Eigen::VectorXd>(y + o, nf_);
  o += nf_;
  v.V = Vec3(y[o], y[o + 1], y[o + 2]);
  v.w = Vec3(y[o + 3], y[o + 4], y[o + 5]);
  o += 6;
  v.eta = Eigen::Map<const Eigen::VectorXd>(y + o, ne_);
  o += ne_;
  v.xf = Eigen::Map<const Eigen::VectorXd>(y + o, nf_);
}

}  // namespace rigflex::rig
