// equation_samples (identification.hpp): the kinematics and loads of the
// carrying frame at the equation times of one history.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "identify/identification.hpp"
#include "rig/median.hpp"
#include "rig/pose_fit.hpp"
#include "rig/skew.hpp"

namespace rigflex::identify {
namespace {

// Stretches of uniform sampling: a step more than half a sample off the
// median (a dropped sample, a logger pause) ends one. Smaller deviations
// are time stamps rounded by the logger (300 Hz stamped in whole ms: steps
// of 3 and 4 ms) over a uniform clock: the samples count, not the stamps,
// and the sample interval is the mean step inside the stretches.
struct UniformStretches {
  std::vector<Eigen::Index> start;  // per sample, the first sample of its stretch
  double step = 0;                  // s, the sample interval
};

UniformStretches uniform_stretches(const Eigen::VectorXd& t) {
  const Eigen::Index S = t.size();
  const double h_median = rig::median_step(t);
  UniformStretches u;
  u.start.resize(static_cast<size_t>(S));
  u.start[0] = 0;
  double inside = 0;
  Eigen::Index steps = 0;
  for (Eigen::Index k = 1; k < S; ++k) {
    const double dt = t(k) - t(k - 1);
    const bool uniform = std::abs(dt - h_median) < 0.5 * h_median;
    u.start[static_cast<size_t>(k)] = uniform ? u.start[static_cast<size_t>(k - 1)] : k;
    if (uniform) inside += dt, ++steps;
  }
  u.step = steps ? inside / static_cast<double>(steps) : h_median;
  return u;
}

// The lower joints b_i in frame c, and their rms distance from their centroid (the rig's size).
rig::JointPoints nominal_lower_joints(const IdentificationRig& rig) {
  rig::JointPoints b = rig::JointPoints::Zero(3, rig.rods());
  for (int i = 0; i < rig.rods(); ++i) b.col(i) = rig.geometry.rods[i].lower;
  return b;
}

double rms_spread(const rig::JointPoints& b) {
  const int n = static_cast<int>(b.cols());
  return std::sqrt((b.colwise() - b.rowwise().mean()).squaredNorm() / n);
}

// One equation time's smoothed signals and the scratch of its fits, sized once.
struct Smoothed {
  explicit Smoothed(int n) : x0(3 * n + 6), x1(3 * n), x2(3 * n), rhs_a(3 * n), G(3 * n, 6) {}
  Eigen::VectorXd x0;      // joints (3 per rod), then the force and the moment
  Eigen::VectorXd x1, x2;  // the joints' first and second derivatives
  Eigen::VectorXd rhs_a;
  Eigen::MatrixXd G;
};

void smooth_at(const SavitzkyGolayKernels& kern, const MotionSeries& motion, Eigen::Index k, Smoothed& s) {
  const Eigen::Index nj = s.x1.size();
  for (Eigen::Index c = 0; c < nj; ++c) {
    const SavitzkyGolayEstimate est = savitzky_golay_at(kern, &motion.joints(k, c));
    s.x0(c) = est.value;
    s.x1(c) = est.first;
    s.x2(c) = est.second;
  }
  for (Eigen::Index c = 0; c < 3; ++c) {
    s.x0(nj + c) = savitzky_golay_value_at(kern, &motion.force(k, c));
    s.x0(nj + 3 + c) = savitzky_golay_value_at(kern, &motion.moment(k, c));
  }
}

// Rigid velocity and acceleration fields through the joints, fitted to the
// smoothed derivatives: dB_i = v + w x rho_i, ddB_i - w x (w x rho_i) =
// a + dw x rho_i; everything returned in frame c.
EquationSample rigid_fit(const rig::JointPoints& b, const rig::PoseFit& pose, Smoothed& s) {
  const int n = static_cast<int>(b.cols());
  const Eigen::Index nj = 3 * n;
  for (int i = 0; i < n; ++i) {
    const rig::Vec3 rho = pose.R * b.col(i);
    s.G.block<3, 3>(3 * i, 0).setIdentity();
    s.G.block<3, 3>(3 * i, 3) = -rig::skew(rho);
  }
  const Eigen::Matrix<double, 6, 6> GtG = s.G.transpose() * s.G;
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(GtG);
  const Eigen::Matrix<double, 6, 1> vel = ldlt.solve(s.G.transpose() * s.x1);
  const rig::Vec3 w = vel.tail<3>();
  for (int i = 0; i < n; ++i) {
    const rig::Vec3 rho = pose.R * b.col(i);
    s.rhs_a.segment<3>(3 * i) = s.x2.segment<3>(3 * i) - w.cross(w.cross(rho));
  }
  const Eigen::Matrix<double, 6, 1> acc = ldlt.solve(s.G.transpose() * s.rhs_a);
  EquationSample e;
  e.R = pose.R;
  const Eigen::Matrix3d Rt = pose.R.transpose();
  e.w = Rt * w;
  e.dw = Rt * acc.tail<3>();
  e.a = Rt * acc.head<3>();
  const rig::Vec3 F = s.x0.segment<3>(nj);
  e.force = Rt * F;
  e.moment = Rt * (s.x0.segment<3>(nj + 3) - pose.r.cross(F));
  e.pose_residual = pose.rms_residual;
  return e;
}

}  // namespace

std::vector<EquationSample> equation_samples(const IdentificationRig& rig, const MotionSeries& motion,
                                             const IdentificationOptions& options) {
  options.validate();
  const int n = rig.rods();
  const Eigen::Index S = motion.t.size();
  std::vector<EquationSample> out;
  if (S < 3) return out;
  const UniformStretches stretches = uniform_stretches(motion.t);
  const double h = stretches.step;
  const SavitzkyGolayKernels kern = savitzky_golay_kernels(options.differentiation, h);
  const int hw = kern.half_width;
  const int stride = std::max(1, static_cast<int>(std::lround(1.0 / (h * options.equation_rate_hz))));

  const rig::JointPoints b = nominal_lower_joints(rig);
  const double size = rms_spread(b);
  rig::JointPoints Bs = rig::JointPoints::Zero(3, n);
  Smoothed s(n);
  for (Eigen::Index k = hw; k + hw < S; k += stride) {
    if (stretches.start[static_cast<size_t>(k + hw)] > k - hw) continue;
    smooth_at(kern, motion, k, s);
    for (int i = 0; i < n; ++i) Bs.col(i) = s.x0.segment<3>(3 * i);
    const rig::PoseFit pose = rig::fit_pose(b, Bs);
    // Encoders and lengths that no rigid carrying frame can satisfy (angles
    // in degrees, swapped columns, another rig's file) are not a noisy fit.
    if (pose.rms_residual > 0.05 * size) {
      throw rig::RecordError(k, "", "the rod directions put the lower joints " +
                                        std::to_string(1e3 * pose.rms_residual) +
                                        " mm (rms) away from any pose of the carrying frame: the encoder angles do "
                                        "not fit the rig's geometry (check units, column order and the rig file)");
    }
    out.push_back(rigid_fit(b, pose, s));
  }
  return out;
}

}  // namespace rigflex::identify
