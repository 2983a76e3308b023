#include "rig/skew.hpp"
#include "identify/identification.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "identify/mass_statistics.hpp"
#include "rig/pose_fit.hpp"

namespace rigflex::identify {
namespace {

// J v as a linear map of (Jxx, Jyy, Jzz, Jxy, Jxz, Jyz).
Eigen::Matrix<double, 3, 6> inertia_map(const rig::Vec3& v) {
  Eigen::Matrix<double, 3, 6> L;
  L << v.x(), 0, 0, v.y(), v.z(), 0,  //
      0, v.y(), 0, v.x(), 0, v.z(),   //
      0, 0, v.z(), 0, v.x(), v.y();
  return L;
}

Eigen::Matrix3d inertia_matrix(const Eigen::Matrix<double, 6, 1>& J) {
  Eigen::Matrix3d T;
  T << J(0), J(3), J(4), J(3), J(1), J(5), J(4), J(5), J(2);
  return T;
}

Eigen::Matrix3d point_inertia(double m, const rig::Vec3& b) {
  return m * (b.squaredNorm() * Eigen::Matrix3d::Identity() - b * b.transpose());
}

double median_step(const Eigen::VectorXd& t) {
  std::vector<double> dt(static_cast<size_t>(t.size() - 1));
  for (Eigen::Index k = 0; k + 1 < t.size(); ++k) dt[static_cast<size_t>(k)] = t(k + 1) - t(k);
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

}  // namespace

void IdentificationOptions::validate() const {
  differentiation.validate();
  if (!(equation_rate_hz > 0) || !std::isfinite(equation_rate_hz)) {
    throw std::invalid_argument("identification.equation_rate_hz must be positive");
  }
  if (!imposed_cog.allFinite()) throw std::invalid_argument("identification.imposed_cog must be finite");
  if (!(observability_limit > 0)) throw std::invalid_argument("identification.observability_limit must be positive");
}

std::vector<EquationSample> equation_samples(const IdentificationRig& rig, const MotionSeries& motion,
                                             const IdentificationOptions& options) {
  options.validate();
  const int n = rig.rods();
  const Eigen::Index S = motion.t.size();
  std::vector<EquationSample> out;
  if (S < 3) return out;
  const double h_median = median_step(motion.t);
  // Stretches of uniform sampling: a step more than half a sample off the
  // median (a dropped sample, a logger pause) ends one. Smaller deviations
  // are time stamps rounded by the logger (300 Hz stamped in whole ms: steps
  // of 3 and 4 ms) over a uniform clock: the samples count, not the stamps,
  // and the sample interval is the mean step inside the stretches.
  std::vector<Eigen::Index> segment_start(static_cast<size_t>(S));
  segment_start[0] = 0;
  double inside = 0;
  Eigen::Index steps = 0;
  for (Eigen::Index k = 1; k < S; ++k) {
    const double dt = motion.t(k) - motion.t(k - 1);
    const bool uniform = std::abs(dt - h_median) < 0.5 * h_median;
    segment_start[static_cast<size_t>(k)] = uniform ? segment_start[static_cast<size_t>(k - 1)] : k;
    if (uniform) inside += dt, ++steps;
  }
  const double h = steps ? inside / static_cast<double>(steps) : h_median;
  const SavitzkyGolayKernels kern = savitzky_golay_kernels(options.differentiation, h);
  const int hw = kern.half_width;
  const int stride = std::max(1, static_cast<int>(std::lround(1.0 / (h * options.equation_rate_hz))));
  const Eigen::Index nj = 3 * n;

  rig::JointPoints b = rig::JointPoints::Zero(3, n), Bs = rig::JointPoints::Zero(3, n);
  for (int i = 0; i < n; ++i) b.col(i) = rig.geometry.rods[i].lower;
  const double size = std::sqrt((b.colwise() - b.rowwise().mean()).squaredNorm() / n);
  Eigen::VectorXd x0(nj + 6), x1(nj), x2(nj), rhs_a(nj);
  Eigen::MatrixXd G(nj, 6);
  for (Eigen::Index k = hw; k + hw < S; k += stride) {
    if (segment_start[static_cast<size_t>(k + hw)] > k - hw) continue;
    for (Eigen::Index c = 0; c < nj; ++c) {
      const SavitzkyGolayEstimate est = savitzky_golay_at(kern, &motion.joints(k, c));
      x0(c) = est.value;
      x1(c) = est.first;
      x2(c) = est.second;
    }
    for (Eigen::Index c = 0; c < 3; ++c) {
      x0(nj + c) = savitzky_golay_value_at(kern, &motion.force(k, c));
      x0(nj + 3 + c) = savitzky_golay_value_at(kern, &motion.moment(k, c));
    }
    for (int i = 0; i < n; ++i) Bs.col(i) = x0.segment<3>(3 * i);
    const rig::PoseFit pose = rig::fit_pose(b, Bs);
    // Encoders and lengths that no rigid carrying frame can satisfy (angles
    // in degrees, swapped columns, another rig's file) are not a noisy fit.
    if (pose.rms_residual > 0.05 * size) {
      throw RecordError(k, "", "the rod directions put the lower joints " + std::to_string(1e3 * pose.rms_residual) +
                                   " mm (rms) away from any pose of the carrying frame: the encoder angles do not "
                                   "fit the rig's geometry (check units, column order and the rig file)");
    }
    // Rigid velocity and acceleration fields through the joints:
    // dB_i = v + w x rho_i, ddB_i - w x (w x rho_i) = a + dw x rho_i.
    for (int i = 0; i < n; ++i) {
      const rig::Vec3 rho = pose.R * b.col(i);
      G.block<3, 3>(3 * i, 0).setIdentity();
      G.block<3, 3>(3 * i, 3) = -rig::skew(rho);
    }
    const Eigen::Matrix<double, 6, 6> GtG = G.transpose() * G;
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(GtG);
    const Eigen::Matrix<double, 6, 1> vel = ldlt.solve(G.transpose() * x1);
    const rig::Vec3 w = vel.tail<3>();
    for (int i = 0; i < n; ++i) {
      const rig::Vec3 rho = pose.R * b.col(i);
      rhs_a.segment<3>(3 * i) = x2.segment<3>(3 * i) - w.cross(w.cross(rho));
    }
    const Eigen::Matrix<double, 6, 1> acc = ldlt.solve(G.transpose() * rhs_a);
    EquationSample e;
    e.R = pose.R;
    const Eigen::Matrix3d Rt = pose.R.transpose();
    e.w = Rt * w;
    e.dw = Rt * acc.tail<3>();
    e.a = Rt * acc.head<3>();
    const rig::Vec3 F = x0.segment<3>(nj);
    e.force = Rt * F;
    e.moment = Rt * (x0.segment<3>(nj + 3) - pose.r.cross(F));
    e.pose_residual = pose.rms_residual;
    out.push_back(e);
  }
  return out;
}

IdentificationResult solve_mass_properties(const std::vector<EquationSample>& samples, double mass,
                                           const std::vector<std::pair<double, rig::Vec3>>& point_masses, double gravity,
                                           double size, const IdentificationOptions& options) {
  options.validate();
  if (!(mass > 0) || !(size > 0) || !(gravity > 0)) throw std::invalid_argument("solve_mass_properties: bad scales");
  const auto& names = mass_component_names();
  double m_id = mass;
  rig::Vec3 s_points = rig::Vec3::Zero();
  Eigen::Matrix3d J_points = Eigen::Matrix3d::Zero();
  for (const auto& [m, b] : point_masses) {
    m_id += m;
    s_points += m * b;
    J_points += point_inertia(m, b);
  }

  // Unknowns kept: c components not imposed, then the six inertia components.
  std::vector<int> fixed;
  if (options.cog_constraint == CogConstraint::in_plane) fixed = {0, 1};
  if (options.cog_constraint == CogConstraint::full) fixed = {0, 1, 2};
  const rig::Vec3 c_id_imposed = (mass * options.imposed_cog + s_points) / m_id;
  std::vector<int> free;
  for (int j = 0; j < 9; ++j) {
    if (std::find(fixed.begin(), fixed.end(), j) == fixed.end()) free.push_back(j);
  }
  const int nu = static_cast<int>(free.size());
  const Eigen::Index rows = 6 * static_cast<Eigen::Index>(samples.size());

  IdentificationResult res;
  res.equations = static_cast<int>(samples.size());
  if (rows < 9) {
    std::string list;
    for (int j : free) {
      res.unobservable.push_back(names[static_cast<size_t>(j)]);
      list += (list.empty() ? "" : ", ") + res.unobservable.back();
    }
    res.message = "too few equation times (" + std::to_string(samples.size()) + ") for " + std::to_string(nu) +
                  " unknowns: the record is shorter than the differentiation window; not observable: " + list;
    return res;
  }

  // Rows made dimensionless by the weight (and the rig size for moments),
  // columns by the physical scale of each unknown, so that singular values
  // and standard deviations compare across units.
  const double row_force = 1.0 / (m_id * gravity), row_moment = row_force / size;
  Eigen::Matrix<double, 9, 1> col_scale;
  col_scale << size, size, size, Eigen::Matrix<double, 6, 1>::Constant(m_id * size * size);
  Eigen::MatrixXd A(rows, nu);
  Eigen::VectorXd b(rows);
  Eigen::Index row = 0;
  for (const EquationSample& e : samples) {
    const rig::Vec3 gc = e.R.transpose() * rig::Vec3(0, 0, -gravity);
    Eigen::Matrix<double, 6, 9> a = Eigen::Matrix<double, 6, 9>::Zero();
    Eigen::Matrix<double, 6, 1> rhs;
    a.block<3, 3>(0, 0) = m_id * (rig::skew(e.dw) + rig::skew(e.w) * rig::skew(e.w));
    rhs.head<3>() = e.force + m_id * (gc - e.a);
    a.block<3, 3>(3, 0) = -m_id * rig::skew(e.a - gc);
    a.block<3, 6>(3, 3) = inertia_map(e.dw) + rig::skew(e.w) * inertia_map(e.w);
    rhs.tail<3>() = e.moment;
    for (int j : fixed) rhs -= a.col(j) * c_id_imposed(j);
    for (int i = 0; i < 6; ++i) {
      const double w = i < 3 ? row_force : row_moment;
      for (int q = 0; q < nu; ++q) A(row + i, q) = w * a(i, free[q]) * col_scale(free[q]);
      b(row + i) = w * rhs(i);
    }
    row += 6;
  }

  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Rf = qr.matrixQR().topRows(nu).triangularView<Eigen::Upper>();
  const Eigen::VectorXd qtb = (qr.householderQ().transpose() * b).head(nu);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Rf, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  res.singular_values = sv;
  res.condition_number = sv(nu - 1) > 0 ? sv(0) / sv(nu - 1) : std::numeric_limits<double>::infinity();

  const Eigen::VectorXd y = svd.solve(qtb);
  const Eigen::VectorXd resid = A * y - b;
  const double dof = std::max<double>(1.0, static_cast<double>(rows - nu));
  const double s = resid.norm() / std::sqrt(dof);
  for (int i = 0; i < nu; ++i) {
    const bool rank_lost = sv(i) <= 1e-12 * sv(0);
    if (!rank_lost && s / sv(i) <= options.observability_limit) continue;
    for (int q = 0; q < nu; ++q) {
      const std::string name = names[static_cast<size_t>(free[q])];
      if (std::abs(svd.matrixV()(q, i)) > 0.3 &&
          std::find(res.unobservable.begin(), res.unobservable.end(), name) == res.unobservable.end()) {
        res.unobservable.push_back(name);
      }
    }
  }
  if (!res.unobservable.empty()) {
    std::string list;
    for (const auto& n : res.unobservable) list += (list.empty() ? "" : ", ") + n;
    res.message = "the records do not excite the unknowns enough: " + list +
                  " not observable (condition number " + std::to_string(res.condition_number) +
                  "); record longer or larger swings, or impose the CoG from the static procedure";
    return res;
  }
  res.observable = true;

  Eigen::Matrix<double, 9, 1> x;
  for (int j : fixed) x(j) = c_id_imposed(j);
  for (int q = 0; q < nu; ++q) x(free[q]) = y(q) * col_scale(free[q]);
  const Eigen::MatrixXd cov = s * s * svd.matrixV() * sv.cwiseInverse().cwiseAbs2().asDiagonal() *
                              svd.matrixV().transpose();
  res.standard_deviation.fill(0.0);
  for (int q = 0; q < nu; ++q) {
    res.standard_deviation[static_cast<size_t>(free[q])] = std::sqrt(cov(q, q)) * col_scale(free[q]);
  }
  double sf = 0, sm = 0;
  for (Eigen::Index r = 0; r < rows; ++r) {
    const bool force_row = (r % 6) < 3;
    const double v = resid(r) / (force_row ? row_force : row_moment);
    (force_row ? sf : sm) += v * v;
  }
  res.force_residual_rms = std::sqrt(sf / (rows / 2.0));
  res.moment_residual_rms = std::sqrt(sm / (rows / 2.0));

  // The rods' moving thirds were part of the identified system.
  const rig::Vec3 c_id = x.head<3>();
  const Eigen::Matrix3d J_P_id = inertia_matrix(x.tail<6>());
  res.properties.mass = mass;
  res.properties.cog = (m_id * c_id - s_points) / mass;
  res.inertia_about_P = J_P_id - J_points;
  res.properties.inertia = res.inertia_about_P - point_inertia(mass, res.properties.cog);
  // The CoG's deviations carry over; the inertia's are quoted about P (the
  // transfer adds the CoG's, second order for the moments).
  for (int j : fixed) res.standard_deviation[static_cast<size_t>(j)] = 0.0;
  for (int j = 0; j < 3; ++j) res.standard_deviation[static_cast<size_t>(j)] *= m_id / mass;

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(res.properties.inertia);
  res.principal_moments = eig.eigenvalues();
  res.principal_axes = eig.eigenvectors();
  if (res.principal_axes.determinant() < 0) res.principal_axes.col(2) *= -1.0;
  const rig::Vec3& p = res.principal_moments;
  res.positive_definite = p(0) > 0;
  const double tol = 1e-9 * p.cwiseAbs().maxCoeff();
  res.triangle_inequality = p(2) <= p(0) + p(1) + tol;
  res.message = "identified from " + std::to_string(samples.size()) + " equation times";
  return res;
}

IdentificationResult identify(const IdentificationRig& rig, const std::vector<const rig::VirtualHistory*>& histories,
                              const IdentificationOptions& options) {
  rig.validate();
  options.validate();
  if (histories.empty()) throw std::invalid_argument("identify: no histories");
  std::vector<EquationSample> samples;
  for (size_t i = 0; i < histories.size(); ++i) {
    MotionSeries motion;
    try {
      motion = motion_series(rig, *histories[i]);
    } catch (RecordError& e) {
      e.set_history(static_cast<int>(i));
      throw;
    }
    try {
      const std::vector<EquationSample> e = equation_samples(rig, motion, options);
      samples.insert(samples.end(), e.begin(), e.end());
    } catch (RecordError& e) {
      e.set_history(static_cast<int>(i));
      throw;
    }
  }
  double pose_sq = 0, pose_max = 0;
  for (const EquationSample& e : samples) {
    pose_sq += e.pose_residual * e.pose_residual;
    pose_max = std::max(pose_max, e.pose_residual);
  }
  std::vector<std::pair<double, rig::Vec3>> points;
  double size2 = 0;
  for (int i = 0; i < rig.rods(); ++i) {
    if (rig.rod_mass(i) > 0) points.emplace_back(rig.rod_mass(i) / 3.0, rig.geometry.rods[i].lower);
    size2 += rig.geometry.rods[i].lower.squaredNorm();
  }
  const double size = std::sqrt(size2 / rig.rods());
  IdentificationResult res = solve_mass_properties(samples, rig.mass, points, rig.geometry.gravity, size, options);
  res.pose_residual_rms = samples.empty() ? 0.0 : std::sqrt(pose_sq / static_cast<double>(samples.size()));
  res.pose_residual_max = pose_max;
  return res;
}

Eigen::Matrix3d inertia_about(const fe::MassProperties& p, const rig::Vec3& point) {
  return p.inertia + point_inertia(p.mass, p.cog - point);
}

fe::MassProperties subtract_tare(const fe::MassProperties& system, const fe::MassProperties& tare) {
  fe::MassProperties body;
  body.mass = system.mass - tare.mass;
  if (!(body.mass > 0)) {
    throw std::invalid_argument("tare: its mass (" + std::to_string(tare.mass) + " kg) is not below the system's (" +
                                std::to_string(system.mass) + " kg)");
  }
  body.cog = (system.mass * system.cog - tare.mass * tare.cog) / body.mass;
  const Eigen::Matrix3d J_P = inertia_about(system, rig::Vec3::Zero()) - inertia_about(tare, rig::Vec3::Zero());
  body.inertia = J_P - point_inertia(body.mass, body.cog);
  return body;
}

}  // namespace rigflex::identify
