#include "identify/identification_kinematics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rig/encoder.hpp"
#include "rig/pose_fit.hpp"

namespace rigflex::identify {
namespace {

void check_record(const IdentificationRig& rig, const rig::Record& h) {
  const int n = rig.rods();
  const Eigen::Index s = h.t.size();
  if (h.force.cols() != n || h.alpha.cols() != n || h.beta.cols() != n) {
    throw rig::RecordError(-1, "", "the record has " + std::to_string(h.force.cols()) + " rods, the rig " +
                                  std::to_string(n));
  }
  if (h.force.rows() != s || h.alpha.rows() != s || h.beta.rows() != s) {
    throw rig::RecordError(-1, "", "the record's channels have different lengths");
  }
}

// What motion_series works with at one sample, sized once for n rods.
struct SampleWork {
  SampleWork(const IdentificationRig& rig, int n)
      : b_nominal(rig::JointPoints::Zero(3, n)),
        B(rig::JointPoints::Zero(3, n)),
        f(3, n),
        spring(n),
        upper_load(3 * n),
        lower_load(3 * n),
        dA(rig.fixed_compliance.size() ? 3 * n : 0),
        eta(rig.carrying_frame ? rig.carrying_frame->omega2.size() : 0),
        d(3 * n),
        u(n) {
    for (int i = 0; i < n; ++i) b_nominal.col(i) = rig.geometry.rods[i].lower;
    sample.force.resize(n);
    sample.alpha.resize(n);
    sample.beta.resize(n);
  }
  rig::JointPoints b_nominal, B;
  Eigen::Matrix3Xd f;  // each rod's load on the identified system
  Eigen::VectorXd spring, upper_load, lower_load, dA, eta, d;
  rig::SensorSample sample;
  std::vector<rig::Vec3> u;  // rod directions
};

// Sample k as the sensors saw it, the effects' measurement chain undone.
void read_sample(const IdentificationRig& rig, const rig::Record& record, Eigen::Index k, rig::SensorSample& sample) {
  sample.t = record.t(k);
  sample.force = record.force.row(k).transpose();
  sample.alpha = record.alpha.row(k).transpose();
  sample.beta = record.beta.row(k).transpose();
  for (const auto& e : rig.measurement_chain) e->unmeasure(sample);
}

// The rod directions from the encoders and the rods' loads: the spring
// force, the load on the identified system, the load on the upper joint.
void rod_loads(const IdentificationRig& rig, Eigen::Index k, SampleWork& w) {
  const double g = rig.geometry.gravity;
  const rig::Vec3 gvec(0, 0, -g);
  const rig::SensorSample& sample = w.sample;
  for (int i = 0; i < rig.rods(); ++i) {
    w.u[i] = rig::rod_direction(rig.geometry.rods[i].encoder_axis, {sample.alpha(i), sample.beta(i)});
    if (!(w.u[i].z() < 0)) {
      // u_z = -cos(alpha) cos(beta): name the angle that turned the rod up.
      const bool beta_bad = std::cos(sample.beta(i)) <= 0;
      throw rig::RecordError(k, (beta_bad ? "beta" : "alpha") + std::to_string(i + 1),
                             "rod " + std::to_string(i + 1) + " would point above its upper joint: alpha " +
                                 std::to_string(sample.alpha(i)) + " rad, beta " + std::to_string(sample.beta(i)) +
                                 " rad are impossible for a hanging rod (check the encoder columns and units)");
    }
    // The load cell sits at the upper end: it also carries the upper half of the rod's weight along the rod.
    w.spring(i) = sample.force(i) - 0.5 * rig.rod_mass(i) * g * (-w.u[i].z());
    // The moving third of the rod is part of the identified system, so of
    // the half weight the lower joint carries a third is the system's own.
    w.f.col(i) = -w.spring(i) * w.u[i] + (rig.rod_mass(i) / 6.0) * gvec;
    w.upper_load.segment<3>(3 * i) = w.spring(i) * w.u[i];
  }
}

// The lower joints B_i = A_i + L_i u_i (A_i moved by the fixed frame's
// compliance, L_i stretched by the rod's), and the resultant F and its moment M.
void joints_and_resultant(const IdentificationRig& rig, SampleWork& w, rig::Vec3& F, rig::Vec3& M) {
  if (rig.fixed_compliance.size()) w.dA.noalias() = rig.fixed_compliance * w.upper_load;
  F = rig::Vec3::Zero();
  M = rig::Vec3::Zero();
  for (int i = 0; i < rig.rods(); ++i) {
    double L = rig.geometry.rods[i].length;
    if (rig.rod_stiffness.size()) L += w.spring(i) / rig.rod_stiffness(i);
    rig::Vec3 A = rig.geometry.rods[i].upper;
    if (w.dA.size()) A += w.dA.segment<3>(3 * i);
    w.B.col(i) = A + L * w.u[i];
    F += w.f.col(i);
    M += rig::Vec3(w.B.col(i)).cross(rig::Vec3(w.f.col(i)));
  }
}

// The carrying frame's quasi-static joint deformation taken out of B_i. The
// joint deformation needs the loads in frame c, so the pose of the
// undeformed joints serves; the rotation it misses, (deformation / joint
// spacing), changes R d_i by far less than the encoders resolve.
void remove_carrying_frame_deformation(const IdentificationRig& rig, SampleWork& w) {
  const rig::CarryingFrameModel& cf = *rig.carrying_frame;
  const rig::Vec3 gvec(0, 0, -rig.geometry.gravity);
  const rig::PoseFit pose = rig::fit_pose(w.b_nominal, w.B);
  for (int i = 0; i < rig.rods(); ++i) {
    w.lower_load.segment<3>(3 * i) = pose.R.transpose() * (-w.spring(i) * w.u[i] + 0.5 * rig.rod_mass(i) * gvec);
  }
  w.eta.noalias() = cf.psi.transpose() * w.lower_load;
  w.eta.array() /= cf.omega2.array();
  w.d.noalias() = cf.psi * w.eta;
  for (int i = 0; i < rig.rods(); ++i) w.B.col(i) -= pose.R * w.d.segment<3>(3 * i);
}

}  // namespace

MotionSeries motion_series(const IdentificationRig& rig, const rig::Record& record) {
  check_record(rig, record);
  const int n = rig.rods();
  const Eigen::Index S = record.t.size();
  MotionSeries out;
  out.t = record.t;
  out.joints.resize(S, 3 * n);
  out.force.resize(S, 3);
  out.moment.resize(S, 3);
  SampleWork w(rig, n);
  for (Eigen::Index k = 0; k < S; ++k) {
    read_sample(rig, record, k, w.sample);
    rod_loads(rig, k, w);
    rig::Vec3 F, M;
    joints_and_resultant(rig, w, F, M);
    out.force.row(k) = F.transpose();
    out.moment.row(k) = M.transpose();
    if (rig.carrying_frame) remove_carrying_frame_deformation(rig, w);
    for (int i = 0; i < n; ++i) out.joints.block<1, 3>(k, 3 * i) = w.B.col(i).transpose();
  }
  return out;
}

}  // namespace rigflex::identify
