#include "diagnose/model_response.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rig/encoder.hpp"
#include "rig/equilibrium.hpp"
#include "rig/generalized_alpha.hpp"
#include "rig/median.hpp"
#include "rig/pose_fit.hpp"
#include "rig/simulation.hpp"

namespace rigflex::diagnose {

std::vector<std::string> channel_names(int rods) {
  std::vector<std::string> names;
  for (const char* prefix : {"F", "alpha", "beta"}) {
    for (int i = 1; i <= rods; ++i) names.push_back(prefix + std::to_string(i));
  }
  return names;
}

Eigen::MatrixXd channels_of(const rig::Record& h) {
  const Eigen::Index n = h.force.cols();
  Eigen::MatrixXd c(h.t.size(), 3 * n);
  c << h.force, h.alpha, h.beta;
  return c;
}

ResponseModel::ResponseModel(const rig::RigModel& model) : system(model), linearization(linearize(system)) {
  double swing = 0, deformation = 0;
  for (const auto& m : linearization.modes) {
    if (m.kind == rig::RigModeKind::swing) swing = std::max(swing, m.frequency_hz);
    if (m.kind == rig::RigModeKind::deformation && deformation == 0) deformation = std::min(m.frequency_hz, kResolveCapHz);
  }
  resolve_hz = model.simulation.resolve_hz > 0 ? model.simulation.resolve_hz : std::max(swing, deformation);
  for (int k = 0; k < static_cast<int>(linearization.modes.size()); ++k) {
    const rig::RigMode& mode = linearization.modes[static_cast<size_t>(k)];
    if (mode.kind == rig::RigModeKind::deformation && mode.frequency_hz <= resolve_hz * (1 + 1e-9)) elastic_modes.push_back(k);
  }
}

namespace {

double yaw_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace

double lowest_swing_hz(const ResponseModel& m) {
  for (const auto& mode : m.linearization.modes) {
    if (mode.kind == rig::RigModeKind::swing) return mode.frequency_hz;
  }
  return 0.0;
}

void swing_initial_state(const ResponseModel& m, const SwingState& s, rig::Configuration& c, rig::Velocity& v,
                         const ElasticState& elastic) {
  const rig::RigSystem& rig = m.system;
  const rig::Configuration& eq = m.linearization.equilibrium.configuration;
  // Hold P's horizontal position and the yaw, let everything else settle.
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(rig.coordinate_count());
  ds.head<3>() = eq.q.conjugate() * rig::Vec3(s(0), s(1), 0.0);
  ds(5) = s(2);
  rig::EquilibriumOptions opt;
  opt.held = {0, 1, 5};
  const rig::Equilibrium held = static_equilibrium(rig, rig.displaced(eq, ds), opt);
  if (!held.converged) throw rig::NoEquilibrium("swing state: " + held.message);
  c = held.configuration;
  // The vertical velocity and the roll and pitch rates that keep the rod
  // lengths: u_i . (v + w x (B_i - P)) = 0 for every rod, by least squares
  // (a minimum-norm solution where rods are parallel).
  v = rig.at_rest();
  const rig::Kinematics k = rig.kinematics(c, v, 0.0);
  const int n = rig.rods();
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const rig::Vec3& u = k.rods[static_cast<size_t>(i)].u;
    const rig::Vec3 arm = k.rods[static_cast<size_t>(i)].B - c.r;
    const rig::Vec3 m_u = arm.cross(u);  // (w x arm) . u = w . (arm x u)
    A.row(i) << u.z(), m_u.x(), m_u.y();
    b(i) = -(u.x() * s(3) + u.y() * s(4) + m_u.z() * s(5));
  }
  const Eigen::Vector3d z = A.completeOrthogonalDecomposition().solve(b);
  const rig::Vec3 vel(s(3), s(4), z(0)), omega(z(1), z(2), s(5));
  v.V = c.q.conjugate() * vel;
  v.w = c.q.conjugate() * omega;
  if (elastic.empty()) return;
  Eigen::VectorXd de = Eigen::VectorXd::Zero(rig.coordinate_count()), rate = de;
  for (size_t k = 0; k < m.elastic_modes.size(); ++k) {
    const Eigen::VectorXd& shape = m.linearization.modes[static_cast<size_t>(m.elastic_modes[k])].shape;
    de += elastic.amplitude(static_cast<Eigen::Index>(k)) * shape;
    rate += elastic.rate(static_cast<Eigen::Index>(k)) * shape;
  }
  rig::Configuration moved;
  rig.displaced(c, de, moved);
  c = moved;
  // Rates of s at small displacement: (V, w) in frame c, then the frames' coordinates.
  v.V += rate.segment<3>(0);
  v.w += rate.segment<3>(3);
  if (rig.elastic_modes() > 0) v.eta += rate.segment(6, rig.elastic_modes());
  if (rig.fixed_dofs() > 0) v.xf += rate.segment(6 + rig.elastic_modes(), rig.fixed_dofs());
}

namespace {

// The swing from state `s` sampled at `t` by either integrator (both have
// reset, advance_to and state).
template <typename Integrator>
Eigen::MatrixXd sampled_channels(Integrator& integ, const ResponseModel& m, const SwingState& s,
                                 const Eigen::VectorXd& t, const ElasticState& elastic) {
  const rig::RigSystem& rig = m.system;
  rig::Configuration c;
  rig::Velocity v;
  swing_initial_state(m, s, c, v, elastic);
  integ.reset(t(0), c, v);
  const int n = rig.rods();
  Eigen::MatrixXd out(t.size(), 3 * n);
  rig::Kinematics kin;
  rig::SensorSample sample;
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    if (k > 0) integ.advance_to(t(k));
    integ.state(c, v);
    read_sensors(rig, c, v, t(k), kin, sample);
    out.row(k) << sample.force.transpose(), sample.alpha.transpose(), sample.beta.transpose();
  }
  return out;
}

}  // namespace

// The rig file's `simulation.method` decides, as in `rigflex simulate`.
Eigen::MatrixXd predict_channels(const ResponseModel& m, const SwingState& s, const Eigen::VectorXd& t,
                                 const ElasticState& elastic) {
  if (t.size() < 2) throw std::invalid_argument("a record needs at least two samples");
  const rig::RigSystem& rig = m.system;
  const rig::SimulationOptions& so = rig.model().simulation;
  if (so.method == rig::IntegrationMethod::bdf) {
    rig::Integrator integ(rig, so);
    return sampled_channels(integ, m, s, t, elastic);
  }
  const double step = generalized_alpha_step(m.linearization, 1.0 / rig::median_step(t), m.resolve_hz);
  rig::GeneralizedAlpha integ(rig, m.linearization, step, so.position_tolerance);
  return sampled_channels(integ, m, s, t, elastic);
}

SwingState swing_state_from_encoders(const ResponseModel& m, const Eigen::VectorXd& t, const Eigen::MatrixXd& channels,
                                     double window_s) {
  const rig::RigSystem& rig = m.system;
  const rig::RigGeometry& g = rig.assembly().geometry;
  const int n = rig.rods();
  const rig::Configuration& eq = m.linearization.equilibrium.configuration;
  const Eigen::Matrix3d Req = eq.q.toRotationMatrix();
  rig::JointPoints body(3, n), world(3, n);
  for (int i = 0; i < n; ++i) body.col(i) = g.rods[static_cast<size_t>(i)].lower;
  std::vector<double> tau;
  std::vector<Eigen::Vector3d> coords;  // x, y, yaw relative to the equilibrium
  rig::SensorSample s;
  for (Eigen::Index k = 0; k < t.size() && (k < 8 || t(k) - t(0) <= window_s); ++k) {
    s.t = t(k);
    s.force = channels.row(k).head(n).transpose();
    s.alpha = channels.row(k).segment(n, n).transpose();
    s.beta = channels.row(k).segment(2 * n, n).transpose();
    for (const auto& e : rig.model().effects) e->unmeasure(s);
    for (int i = 0; i < n; ++i) {
      const rig::RodGeometry& rod = g.rods[static_cast<size_t>(i)];
      const rig::Vec3 u = rig::rod_direction(rod.encoder_axis, rig::EncoderAngles{s.alpha(i), s.beta(i)});
      world.col(i) = rod.upper + rod.length * u;
    }
    const rig::PoseFit p = rig::fit_pose(body, world);
    tau.push_back(t(k) - t(0));
    coords.emplace_back(p.r.x() - eq.r.x(), p.r.y() - eq.r.y(),
                        std::remainder(yaw_of(p.R) - yaw_of(Req), 2.0 * std::numbers::pi));
  }
  // Least-squares quadratic a + b tau + c tau^2 per coordinate.
  Eigen::MatrixXd V(static_cast<Eigen::Index>(tau.size()), 3);
  Eigen::MatrixXd Y(V.rows(), 3);
  for (Eigen::Index k = 0; k < V.rows(); ++k) {
    const double x = tau[static_cast<size_t>(k)];
    V.row(k) << 1.0, x, x * x;
    Y.row(k) = coords[static_cast<size_t>(k)].transpose();
  }
  const Eigen::MatrixXd C = V.colPivHouseholderQr().solve(Y);
  SwingState out;
  out << C(0, 0), C(0, 1), C(0, 2), C(1, 0), C(1, 1), C(1, 2);
  return out;
}

}  // namespace rigflex::diagnose
