#include "identify/identification_kinematics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rig/encoder.hpp"
#include "rig/pose_fit.hpp"

namespace rigflex::identify {
namespace {

void check_record(const IdentificationRig& rig, const rig::VirtualHistory& h) {
  const int n = rig.rods();
  const Eigen::Index s = h.t.size();
  if (h.force.cols() != n || h.alpha.cols() != n || h.beta.cols() != n) {
    throw RecordError(-1, "", "the record has " + std::to_string(h.force.cols()) + " rods, the rig " +
                                  std::to_string(n));
  }
  if (h.force.rows() != s || h.alpha.rows() != s || h.beta.rows() != s) {
    throw RecordError(-1, "", "the record's channels have different lengths");
  }
}

}  // namespace

MotionSeries motion_series(const IdentificationRig& rig, const rig::VirtualHistory& record) {
  check_record(rig, record);
  const int n = rig.rods();
  const Eigen::Index S = record.t.size();
  const double g = rig.geometry.gravity;
  const rig::Vec3 gvec(0, 0, -g);

  MotionSeries out;
  out.t = record.t;
  out.joints.resize(S, 3 * n);
  out.force.resize(S, 3);
  out.moment.resize(S, 3);

  rig::JointPoints b_nominal = rig::JointPoints::Zero(3, n), B = rig::JointPoints::Zero(3, n);
  for (int i = 0; i < n; ++i) b_nominal.col(i) = rig.geometry.rods[i].lower;
  Eigen::Matrix3Xd f(3, n);
  Eigen::VectorXd spring(n), upper_load(3 * n), lower_load(3 * n);
  Eigen::VectorXd dA(rig.fixed_compliance.size() ? 3 * n : 0);
  Eigen::VectorXd eta(rig.carrying_frame ? rig.carrying_frame->omega2.size() : 0), d(3 * n);
  rig::SensorSample sample;
  sample.force.resize(n);
  sample.alpha.resize(n);
  sample.beta.resize(n);
  std::vector<rig::Vec3> u(n);

  for (Eigen::Index k = 0; k < S; ++k) {
    sample.t = record.t(k);
    sample.force = record.force.row(k).transpose();
    sample.alpha = record.alpha.row(k).transpose();
    sample.beta = record.beta.row(k).transpose();
    for (const auto& e : rig.measurement_chain) e->unmeasure(sample);

    for (int i = 0; i < n; ++i) {
      u[i] = rig::rod_direction(rig.geometry.rods[i].encoder_axis, {sample.alpha(i), sample.beta(i)});
      if (!(u[i].z() < 0)) {
        // u_z = -cos(alpha) cos(beta): name the angle that turned the rod up.
        const bool beta_bad = std::cos(sample.beta(i)) <= 0;
        throw RecordError(k, (beta_bad ? "beta" : "alpha") + std::to_string(i + 1),
                          "rod " + std::to_string(i + 1) + " would point above its upper joint: alpha " +
                              std::to_string(sample.alpha(i)) + " rad, beta " + std::to_string(sample.beta(i)) +
                              " rad are impossible for a hanging rod (check the encoder columns and units)");
      }
      // The load cell sits at the upper end: it also carries the upper half of the rod's weight along the rod.
      spring(i) = sample.force(i) - 0.5 * rig.rod_mass(i) * g * (-u[i].z());
      // The moving third of the rod is part of the identified system, so of
      // the half weight the lower joint carries a third is the system's own.
      f.col(i) = -spring(i) * u[i] + (rig.rod_mass(i) / 6.0) * gvec;
      upper_load.segment<3>(3 * i) = spring(i) * u[i];
    }

    if (rig.fixed_compliance.size()) dA.noalias() = rig.fixed_compliance * upper_load;
    rig::Vec3 F = rig::Vec3::Zero(), M = rig::Vec3::Zero();
    for (int i = 0; i < n; ++i) {
      double L = rig.geometry.rods[i].length;
      if (rig.rod_stiffness.size()) L += spring(i) / rig.rod_stiffness(i);
      rig::Vec3 A = rig.geometry.rods[i].upper;
      if (dA.size()) A += dA.segment<3>(3 * i);
      B.col(i) = A + L * u[i];
      F += f.col(i);
      M += rig::Vec3(B.col(i)).cross(rig::Vec3(f.col(i)));
    }
    out.force.row(k) = F.transpose();
    out.moment.row(k) = M.transpose();

    if (rig.carrying_frame) {
      // The joint deformation needs the loads in frame c, so the pose of the
      // undeformed joints serves; the rotation it misses, (deformation /
      // joint spacing), changes R d_i by far less than the encoders resolve.
      const rig::CarryingFrameModel& cf = *rig.carrying_frame;
      const rig::PoseFit pose = rig::fit_pose(b_nominal, B);
      for (int i = 0; i < n; ++i) {
        lower_load.segment<3>(3 * i) = pose.R.transpose() * (-spring(i) * u[i] + 0.5 * rig.rod_mass(i) * gvec);
      }
      eta.noalias() = cf.psi.transpose() * lower_load;
      eta.array() /= cf.omega2.array();
      d.noalias() = cf.psi * eta;
      for (int i = 0; i < n; ++i) B.col(i) -= pose.R * d.segment<3>(3 * i);
    }
    for (int i = 0; i < n; ++i) out.joints.block<1, 3>(k, 3 * i) = B.col(i).transpose();
  }
  return out;
}

}  // namespace rigflex::identify
