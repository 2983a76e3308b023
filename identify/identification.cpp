#include "identify/identification.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "identify/mass_statistics.hpp"
#include "rig/skew.hpp"

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

// The identified system: the record plus point masses that move with it (the
// rods' moving thirds), whose sums are taken out of the result.
struct PointMassSums {
  double m_id = 0;                                     // kg, record and points
  rig::Vec3 s_points = rig::Vec3::Zero();              // the points' first moment about P
  Eigen::Matrix3d J_points = Eigen::Matrix3d::Zero();  // their inertia about P
};

PointMassSums point_mass_sums(double mass, const std::vector<std::pair<double, rig::Vec3>>& point_masses) {
  PointMassSums p;
  p.m_id = mass;
  for (const auto& [m, b] : point_masses) {
    p.m_id += m;
    p.s_points += m * b;
    p.J_points += point_inertia(m, b);
  }
  return p;
}

// Unknowns kept: c components not imposed, then the six inertia components
// (indices into xG, yG, zG, Jxx, Jyy, Jzz, Jxy, Jxz, Jyz).
struct Unknowns {
  std::vector<int> fixed, free;
  rig::Vec3 c_id_imposed;  // the identified system's CoG where imposed
  int count() const { return static_cast<int>(free.size()); }
};

Unknowns unknowns_of(const IdentificationOptions& options, double mass, const PointMassSums& p) {
  Unknowns u;
  // The imposed components are the leading ones: x, y in plane, then z.
  const int imposed = options.cog_constraint == CogConstraint::full       ? 3
                      : options.cog_constraint == CogConstraint::in_plane ? 2
                                                                          : 0;
  for (int j = 0; j < imposed; ++j) u.fixed.push_back(j);
  u.c_id_imposed = (mass * options.imposed_cog + p.s_points) / p.m_id;
  for (int j = 0; j < 9; ++j) {
    if (std::find(u.fixed.begin(), u.fixed.end(), j) == u.fixed.end()) u.free.push_back(j);
  }
  return u;
}

IdentificationResult too_few_equations(size_t samples, const Unknowns& u) {
  const auto& names = mass_component_names();
  IdentificationResult res;
  res.equations = static_cast<int>(samples);
  std::string list;
  for (int j : u.free) {
    res.unobservable.push_back(names[static_cast<size_t>(j)]);
    list += (list.empty() ? "" : ", ") + res.unobservable.back();
  }
  res.message = "too few equation times (" + std::to_string(samples) + ") for " + std::to_string(u.count()) +
                " unknowns: the record is shorter than the differentiation window; not observable: " + list;
  return res;
}

// Rows made dimensionless by the weight (and the rig size for moments),
// columns by the physical scale of each unknown, so that singular values
// and standard deviations compare across units.
struct ScaledEquations {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  double row_force = 0, row_moment = 0;
  Eigen::Matrix<double, 9, 1> col_scale;
};

ScaledEquations scaled_equations(const std::vector<EquationSample>& samples, double m_id, const Unknowns& u,
                                 double gravity, double size) {
  const int nu = u.count();
  const Eigen::Index rows = 6 * static_cast<Eigen::Index>(samples.size());
  ScaledEquations eq;
  eq.row_force = 1.0 / (m_id * gravity);
  eq.row_moment = eq.row_force / size;
  eq.col_scale << size, size, size, Eigen::Matrix<double, 6, 1>::Constant(m_id * size * size);
  eq.A.resize(rows, nu);
  eq.b.resize(rows);
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
    for (int j : u.fixed) rhs -= a.col(j) * u.c_id_imposed(j);
    for (int i = 0; i < 6; ++i) {
      const double w = i < 3 ? eq.row_force : eq.row_moment;
      for (int q = 0; q < nu; ++q) eq.A(row + i, q) = w * a(i, u.free[q]) * eq.col_scale(u.free[q]);
      eq.b(row + i) = w * rhs(i);
    }
    row += 6;
  }
  return eq;
}

// QR of the scaled system, then the pseudo-inverse through the SVD of its
// triangular factor; s is the residual's standard error.
struct ScaledSolution {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
  Eigen::VectorXd y, resid;
  double s = 0;
};

ScaledSolution solve_scaled(const ScaledEquations& eq, int nu) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(eq.A);
  const Eigen::MatrixXd Rf = qr.matrixQR().topRows(nu).triangularView<Eigen::Upper>();
  const Eigen::VectorXd qtb = (qr.householderQ().transpose() * eq.b).head(nu);
  ScaledSolution sol;
  sol.svd.compute(Rf, Eigen::ComputeFullU | Eigen::ComputeFullV);
  sol.y = sol.svd.solve(qtb);
  sol.resid = eq.A * sol.y - eq.b;
  const double dof = std::max<double>(1.0, static_cast<double>(eq.A.rows() - nu));
  sol.s = sol.resid.norm() / std::sqrt(dof);
  return sol;
}

// The unknowns in a direction whose singular value is lost or too small for
// the residual (standard deviation above the observability limit).
std::vector<std::string> unobservable_unknowns(const ScaledSolution& sol, const Unknowns& u,
                                               const IdentificationOptions& options) {
  const auto& names = mass_component_names();
  const Eigen::VectorXd& sv = sol.svd.singularValues();
  const int nu = u.count();
  std::vector<std::string> out;
  for (int i = 0; i < nu; ++i) {
    const bool rank_lost = sv(i) <= 1e-12 * sv(0);
    if (!rank_lost && sol.s / sv(i) <= options.observability_limit) continue;
    for (int q = 0; q < nu; ++q) {
      const std::string name = names[static_cast<size_t>(u.free[q])];
      if (std::abs(sol.svd.matrixV()(q, i)) > 0.3 && std::find(out.begin(), out.end(), name) == out.end()) {
        out.push_back(name);
      }
    }
  }
  return out;
}

// Standard deviations of the unknowns in physical units (0 for the imposed ones).
void set_standard_deviations(IdentificationResult& res, const ScaledSolution& sol, const ScaledEquations& eq,
                             const Unknowns& u) {
  const Eigen::VectorXd& sv = sol.svd.singularValues();
  const Eigen::MatrixXd cov = sol.s * sol.s * sol.svd.matrixV() * sv.cwiseInverse().cwiseAbs2().asDiagonal() *
                              sol.svd.matrixV().transpose();
  res.standard_deviation.fill(0.0);
  for (int q = 0; q < u.count(); ++q) {
    res.standard_deviation[static_cast<size_t>(u.free[q])] = std::sqrt(cov(q, q)) * eq.col_scale(u.free[q]);
  }
}

// The rms of the force and moment rows, back in N and N m.
void set_residual_rms(IdentificationResult& res, const ScaledSolution& sol, const ScaledEquations& eq) {
  const Eigen::Index rows = eq.A.rows();
  double sf = 0, sm = 0;
  for (Eigen::Index r = 0; r < rows; ++r) {
    const bool force_row = (r % 6) < 3;
    const double v = sol.resid(r) / (force_row ? eq.row_force : eq.row_moment);
    (force_row ? sf : sm) += v * v;
  }
  res.force_residual_rms = std::sqrt(sf / (rows / 2.0));
  res.moment_residual_rms = std::sqrt(sm / (rows / 2.0));
}

// The record's mass properties from the identified system's (the points
// taken out), and the checks of the inertia tensor.
void set_mass_properties(IdentificationResult& res, const Eigen::Matrix<double, 9, 1>& x, double mass,
                         const PointMassSums& p, const Unknowns& u) {
  const rig::Vec3 c_id = x.head<3>();
  const Eigen::Matrix3d J_P_id = inertia_matrix(x.tail<6>());
  res.properties.mass = mass;
  res.properties.cog = (p.m_id * c_id - p.s_points) / mass;
  res.inertia_about_P = J_P_id - p.J_points;
  res.properties.inertia = res.inertia_about_P - point_inertia(mass, res.properties.cog);
  // The CoG's deviations carry over; the inertia's are quoted about P (the
  // transfer adds the CoG's, second order for the moments).
  for (int j : u.fixed) res.standard_deviation[static_cast<size_t>(j)] = 0.0;
  for (int j = 0; j < 3; ++j) res.standard_deviation[static_cast<size_t>(j)] *= p.m_id / mass;

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(res.properties.inertia);
  res.principal_moments = eig.eigenvalues();
  res.principal_axes = eig.eigenvectors();
  if (res.principal_axes.determinant() < 0) res.principal_axes.col(2) *= -1.0;
  const rig::Vec3& pm = res.principal_moments;
  res.positive_definite = pm(0) > 0;
  const double tol = 1e-9 * pm.cwiseAbs().maxCoeff();
  res.triangle_inequality = pm(2) <= pm(0) + pm(1) + tol;
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

IdentificationResult solve_mass_properties(const std::vector<EquationSample>& samples, double mass,
                                           const std::vector<std::pair<double, rig::Vec3>>& point_masses, double gravity,
                                           double size, const IdentificationOptions& options) {
  options.validate();
  if (!(mass > 0) || !(size > 0) || !(gravity > 0)) throw std::invalid_argument("solve_mass_properties: bad scales");
  const PointMassSums p = point_mass_sums(mass, point_masses);
  const Unknowns u = unknowns_of(options, mass, p);
  const int nu = u.count();
  if (6 * static_cast<Eigen::Index>(samples.size()) < 9) return too_few_equations(samples.size(), u);

  const ScaledEquations eq = scaled_equations(samples, p.m_id, u, gravity, size);
  const ScaledSolution sol = solve_scaled(eq, nu);
  IdentificationResult res;
  res.equations = static_cast<int>(samples.size());
  const Eigen::VectorXd& sv = sol.svd.singularValues();
  res.singular_values = sv;
  res.condition_number = sv(nu - 1) > 0 ? sv(0) / sv(nu - 1) : std::numeric_limits<double>::infinity();
  res.unobservable = unobservable_unknowns(sol, u, options);
  if (!res.unobservable.empty()) {
    std::string list;
    for (const auto& n : res.unobservable) list += (list.empty() ? "" : ", ") + n;
    // The test weighs each direction's spread s / sigma_i: a small sigma
    // (little excitation) or a large s (a model that does not fit) fails
    // it alike, so the message names both and gives the residual's size.
    const double b_norm = eq.b.norm();
    const double misfit = b_norm > 0 ? 100.0 * sol.resid.norm() / b_norm : 0.0;
    char residual[64];
    std::snprintf(residual, sizeof residual, "%.3g %%", misfit);
    res.message = "the records do not excite the unknowns enough: " + list + " not observable (condition number " +
                  std::to_string(res.condition_number) + ", equation residual " + residual +
                  " of the equations' size); record longer or larger swings, or impose the CoG from the static "
                  "procedure - or, if that residual is large, the model does not fit the records: an effect the "
                  "records hold and the rig file lacks (or the reverse); compare and diagnose show which";
    return res;
  }
  res.observable = true;

  Eigen::Matrix<double, 9, 1> x;
  for (int j : u.fixed) x(j) = u.c_id_imposed(j);
  for (int q = 0; q < nu; ++q) x(u.free[q]) = sol.y(q) * eq.col_scale(u.free[q]);
  set_standard_deviations(res, sol, eq, u);
  set_residual_rms(res, sol, eq);
  // The rods' moving thirds were part of the identified system.
  set_mass_properties(res, x, mass, p, u);
  res.message = "identified from " + std::to_string(samples.size()) + " equation times";
  return res;
}

IdentificationResult identify(const IdentificationRig& rig, const std::vector<const rig::Record*>& histories,
                              const IdentificationOptions& options) {
  rig.validate();
  options.validate();
  if (histories.empty()) throw std::invalid_argument("identify: no histories");
  std::vector<EquationSample> samples;
  for (size_t i = 0; i < histories.size(); ++i) {
    MotionSeries motion;
    try {
      motion = motion_series(rig, *histories[i]);
    } catch (rig::RecordError& e) {
      e.set_history(static_cast<int>(i));
      throw;
    }
    try {
      const std::vector<EquationSample> e = equation_samples(rig, motion, options);
      samples.insert(samples.end(), e.begin(), e.end());
    } catch (rig::RecordError& e) {
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
