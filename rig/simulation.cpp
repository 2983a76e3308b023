#include "rig/simulation.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "rig/sundials_dense_lu.hpp"
#include "rig/encoder.hpp"
#include "rig/generalized_alpha.hpp"
#include "rig/linearization.hpp"

namespace rigflex::rig {

struct Integrator::Impl {
  const RigSystem& rig;
  SimulationOptions options;
  SUNContext ctx = nullptr;
  N_Vector y = nullptr, atol = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  void* mem = nullptr;
  std::optional<Push> push;
  Configuration c;
  Velocity v;

  explicit Impl(const RigSystem& r, const SimulationOptions& o) : rig(r), options(o) {}
  ~Impl() {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (y) N_VDestroy(y);
    if (atol) N_VDestroy(atol);
    if (ctx) SUNContext_Free(&ctx);
  }
};

namespace {

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed (flag " + std::to_string(flag) + ")");
}

int rig_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* im = static_cast<Integrator::Impl*>(user);
  const RigSystem& rig = im->rig;
  const double* Y = N_VGetArrayPointer(y);
  double* D = N_VGetArrayPointer(ydot);
  rig.unpack(Y, im->c, im->v);
  ExternalLoad load;
  const ExternalLoad* external = im->push ? im->push->load_at(t, load) : nullptr;
  const Eigen::VectorXd Q = rig.generalized_forces(im->c, im->v, t, external);
  const Eigen::VectorXd a = rig.accelerations(im->v, Q);
  const int ne = rig.elastic_modes(), nf = rig.fixed_dofs();
  const Eigen::Quaterniond& q = im->c.q;
  const Vec3 rdot = q.normalized() * im->v.V;
  const Vec3& w = im->v.w;
  int o = 0;
  for (int d = 0; d < 3; ++d) D[o++] = rdot(d);
  const Vec3 qv = q.vec();
  const Vec3 qdot_v = 0.5 * (q.w() * w + qv.cross(w));
  D[o++] = -0.5 * qv.dot(w);
  for (int d = 0; d < 3; ++d) D[o++] = qdot_v(d);
  for (int j = 0; j < ne; ++j) D[o++] = im->v.eta(j);
  for (int j = 0; j < nf; ++j) D[o++] = im->v.xf(j);
  for (int j = 0; j < 6 + ne + nf; ++j) D[o++] = a(j);
  return 0;
}

}  // namespace

Integrator::Integrator(const RigSystem& rig, const SimulationOptions& options) : impl_(new Impl(rig, options)) {
  options.validate();
  Impl& im = *impl_;
  const int n = rig.state_size();
  check(SUNContext_Create(nullptr, &im.ctx), "SUNContext_Create");
  im.y = N_VNew_Serial(n, im.ctx);
  im.atol = N_VNew_Serial(n, im.ctx);
  // Absolute tolerances from one length scale: positions to position_tolerance,
  // rotations to that over the rod length, modal coordinates by their reach
  // at the joints, velocities over the time scale of a 10 Hz vibration.
  double L = 0;
  for (const auto& r : rig.assembly().geometry.rods) L += r.length / rig.rods();
  const double p = options.position_tolerance, w = 2.0 * std::numbers::pi * 10.0;
  const Eigen::VectorXd steps = coordinate_steps(rig);  // a displacement of 1e-6 L at the joints per coordinate
  double* T = N_VGetArrayPointer(im.atol);
  const int nc = rig.coordinate_count();
  int o = 0;
  for (int d = 0; d < 3; ++d) T[o++] = p;
  for (int d = 0; d < 4; ++d) T[o++] = p / L;
  for (int j = 6; j < nc; ++j) T[o++] = p * steps(j) / steps(0);
  for (int j = 0; j < nc; ++j) T[o++] = w * p * (j < 3 ? 1.0 : j < 6 ? 1.0 / L : steps(j) / steps(0));
  N_VConst(0.0, im.y);
  im.A = SUNDenseMatrix(n, n, im.ctx);
  im.LS = make_dense_eigen_solver(im.ctx);
  im.mem = CVodeCreate(CV_BDF, im.ctx);
  if (!im.mem) throw std::runtime_error("CVODE: CVodeCreate failed");
  check(CVodeInit(im.mem, rig_rhs, 0.0, im.y), "CVodeInit");
  check(CVodeSVtolerances(im.mem, options.relative_tolerance, im.atol), "CVodeSVtolerances");
  check(CVodeSetUserData(im.mem, impl_), "CVodeSetUserData");
  check(CVodeSetLinearSolver(im.mem, im.LS, im.A), "CVodeSetLinearSolver");
  check(CVodeSetMaxNumSteps(im.mem, 10000000), "CVodeSetMaxNumSteps");
  if (options.max_step_s > 0) check(CVodeSetMaxStep(im.mem, options.max_step_s), "CVodeSetMaxStep");
  check(CVodeSetMaxOrd(im.mem, options.max_order), "CVodeSetMaxOrd");
}

Integrator::~Integrator() { delete impl_; }

void Integrator::reset(double t, const Configuration& c, const Velocity& v, const Push* push) {
  Impl& im = *impl_;
  im.rig.pack(c, v, N_VGetArrayPointer(im.y));
  im.push = push ? std::optional<Push>(*push) : std::nullopt;
  check(CVodeReInit(im.mem, t, im.y), "CVodeReInit");
  if (push) {
    check(CVodeSetStopTime(im.mem, t + push->duration_s), "CVodeSetStopTime");
  } else {
    // SUNDIALS 6.4 has no CVodeClearStopTime; a stop time beyond any record does the same.
    check(CVodeSetStopTime(im.mem, 1e300), "CVodeSetStopTime");
  }
  t_ = t;
}

void Integrator::advance_to(double t_out) {
  Impl& im = *impl_;
  if (t_out == t_) return;
  sunrealtype reached = t_;
  const int flag = CVode(im.mem, t_out, im.y, &reached, CV_NORMAL);
  if (flag < 0) {
    char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
    const std::string why = std::string("CVode failed (") + (name ? name : "?") + ")";
    std::free(name);
    throw IntegrationFailure("CVODE BDF", reached, why);
  }
  t_ = reached;
}

void Integrator::state(Configuration& c, Velocity& v) const { impl_->rig.unpack(N_VGetArrayPointer(impl_->y), c, v); }

const IntegratorStatistics& Integrator::statistics() const {
  long v = 0;
  CVodeGetNumSteps(impl_->mem, &v);
  stats_.steps = v;
  CVodeGetNumRhsEvals(impl_->mem, &v);
  stats_.rhs_evaluations = v;
  CVodeGetNumJacEvals(impl_->mem, &v);
  stats_.jacobian_evaluations = v;
  CVodeGetNumErrTestFails(impl_->mem, &v);
  stats_.error_test_failures = v;
  CVodeGetNumLinSolvSetups(impl_->mem, &v);
  stats_.linear_setups = v;
  CVodeGetNumNonlinSolvIters(impl_->mem, &v);
  stats_.newton_iterations = v;
  return stats_;
}

SensorSample read_sensors(const RigSystem& rig, const Configuration& c, const Velocity& v, double t) {
  Kinematics k;
  SensorSample s;
  read_sensors(rig, c, v, t, k, s);
  return s;
}

void read_sensors(const RigSystem& rig, const Configuration& c, const Velocity& v, double t, Kinematics& k,
                  SensorSample& s) {
  rig.kinematics(c, v, t, k);
  const int n = rig.rods();
  s.t = t;
  s.force.resize(n);
  s.alpha.resize(n);
  s.beta.resize(n);
  const double g = rig.assembly().geometry.gravity;
  for (int i = 0; i < n; ++i) {
    const RodKinematics& r = k.rods[i];
    s.force(i) = r.force + 0.5 * rig.assembly().rod_mass[i] * g * (-r.u.z());
    const EncoderAngles a = encoder_angles(rig.model().geometry.rods[i].encoder_axis, r.u);
    s.alpha(i) = a.alpha;
    s.beta(i) = a.beta;
  }
  for (const auto& e : rig.model().effects) e->measure(s);
}

namespace {

double quantize(double x, double step) { return step > 0 ? step * std::round(x / step) : x; }

Configuration released_from(const RigSystem& rig, const Configuration& eq, const InitialCondition& ic) {
  // Hold P's horizontal position and the yaw where the operator holds them,
  // let everything else settle.
  Eigen::VectorXd s = Eigen::VectorXd::Zero(rig.coordinate_count());
  const Vec3 d_c = eq.q.conjugate() * Vec3(ic.x, ic.y, 0.0);
  s.segment<3>(0) = d_c;
  s(5) = ic.yaw;
  EquilibriumOptions opt;
  opt.held = {0, 1, 5};
  const Equilibrium held = static_equilibrium(rig, rig.displaced(eq, s), opt);
  if (!held.converged) throw NoEquilibrium("initial condition: " + held.message);
  return held.configuration;
}

template <class Stepper>
Record record(const RigSystem& rig, Stepper& integ, const Configuration& equilibrium,
                      const HistoryRequest& request, IntegratorStatistics* statistics) {
  const SensorOptions& sensors = rig.model().sensors;
  double t_release = 0.0;
  Record h;
  if (request.push) {
    integ.reset(0.0, equilibrium, rig.at_rest(), &*request.push);
    integ.advance_to(request.push->duration_s);
    Configuration c;
    Velocity v;
    integ.state(c, v);
    t_release = request.push->duration_s;
    integ.reset(t_release, c, v);
  } else if (request.initial) {
    const Configuration c = released_from(rig, equilibrium, *request.initial);
    Velocity v = rig.at_rest();
    v.V = c.q.conjugate() * request.initial->velocity;
    v.w = c.q.conjugate() * request.initial->angular_velocity;
    integ.reset(0.0, c, v);
  } else {
    integ.reset(0.0, equilibrium, rig.at_rest());
  }
  const double fs = sensors.sample_rate_hz;
  const Eigen::Index samples = record_samples(request.duration_s, fs);
  const int n = rig.rods();
  h.t.resize(samples);
  h.force.resize(samples, n);
  h.alpha.resize(samples, n);
  h.beta.resize(samples, n);
  h.sample_rate_hz = fs;
  std::mt19937_64 gen(request.noise_seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double angle_step = sensors.encoder_bits > 0 ? 2.0 * std::numbers::pi / std::ldexp(1.0, sensors.encoder_bits) : 0.0;
  Configuration c;
  Velocity v;
  Kinematics kin;
  SensorSample s;
  for (Eigen::Index k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / fs;
    integ.advance_to(t_release + t);
    integ.state(c, v);
    read_sensors(rig, c, v, t_release + t, kin, s);
    h.t(k) = t;
    for (int i = 0; i < n; ++i) {
      h.force(k, i) = quantize(s.force(i) + sensors.force_noise_n * normal(gen), sensors.force_resolution_n);
      h.alpha(k, i) = quantize(s.alpha(i) + sensors.angle_noise_rad * normal(gen), angle_step);
      h.beta(k, i) = quantize(s.beta(i) + sensors.angle_noise_rad * normal(gen), angle_step);
    }
  }
  if (statistics) *statistics = integ.statistics();
  return h;
}

}  // namespace

Record simulate_history(const RigSystem& rig, const Configuration& equilibrium, const HistoryRequest& request,
                                IntegratorStatistics* statistics) {
  const SimulationOptions& options = rig.model().simulation;
  if (options.method == IntegrationMethod::bdf) {
    Integrator integ(rig, options);
    return record(rig, integ, equilibrium, request, statistics);
  }
  std::optional<Linearization> own;
  const Linearization* lin = request.linearization;
  if (!lin) lin = &own.emplace(linearize(rig));
  GeneralizedAlpha integ(rig, *lin,
                         generalized_alpha_step(*lin, rig.model().sensors.sample_rate_hz, options.resolve_hz),
                         options.position_tolerance);
  return record(rig, integ, equilibrium, request, statistics);
}

std::uint64_t noise_seed(std::uint64_t seed, int set, int history) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(set), static_cast<std::uint32_t>(history), 0x6e6f6973u};
  std::uint32_t words[2];
  seq.generate(words, words + 2);
  return (static_cast<std::uint64_t>(words[0]) << 32) | words[1];
}

Push draw_push(const RigSystem& rig, std::uint64_t seed, int set, int history) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(set), static_cast<std::uint32_t>(history), 0x70757368u};
  std::mt19937_64 gen(seq);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const ReleaseOptions& r = rig.model().release;
  const double phi = 2.0 * std::numbers::pi * unit(gen);
  const double acc = r.push_acceleration[0] + (r.push_acceleration[1] - r.push_acceleration[0]) * unit(gen);
  const double yaw = r.push_yaw_acceleration * (2.0 * unit(gen) - 1.0);
  Push p;
  p.duration_s = r.push_duration_s;
  p.force = rig.assembly().body.mass * acc * Vec3(std::cos(phi), std::sin(phi), 0.0);
  p.moment = Vec3(0.0, 0.0, rig.assembly().body.inertia(2, 2) * yaw);
  return p;
}

Eigen::Index record_samples(double duration_s, double sample_rate_hz) {
  if (!(duration_s > 0) || !(sample_rate_hz > 0)) {
    throw std::invalid_argument("a record needs a positive duration and sample rate");
  }
  // Checked in floating point: the count itself would overflow an integer
  // (a duration of 1e17 s gave a record of no samples).
  const double n = std::floor(duration_s * sample_rate_hz + 1e-9) + 1.0;
  if (!(n <= kMaxRecordSamples)) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "a record of %g s at %g Hz would hold %.3g samples; at most %.3g are simulated per record "
                  "(%.3g h at this rate): shorten the duration",
                  duration_s, sample_rate_hz, n, kMaxRecordSamples, kMaxRecordSamples / sample_rate_hz / 3600.0);
    throw std::invalid_argument(msg);
  }
  return static_cast<Eigen::Index>(n);
}

void MeasurementOptions::validate() const {
  if (sets < 1) throw std::invalid_argument("sets must be at least 1");
  if (histories < 1) throw std::invalid_argument("histories must be at least 1");
  // A measurement is some sets of a few histories; far more is a typing slip
  // (2e9 histories ran until killed).
  if (static_cast<double>(sets) * histories > kMaxHistories) {
    throw std::invalid_argument("sets x histories = " + std::to_string(static_cast<long long>(sets) * histories) +
                                " records; at most " + std::to_string(static_cast<long>(kMaxHistories)) +
                                " are simulated in one run");
  }
  if (!(duration_s > 0)) throw std::invalid_argument("duration must be positive");
}

std::vector<std::vector<Record>> simulate_measurement(const RigSystem& rig, const MeasurementOptions& options) {
  options.validate();
  record_samples(options.duration_s, rig.model().sensors.sample_rate_hz);  // refused before the equilibrium's work
  std::optional<Linearization> lin;
  Configuration eq;
  if (rig.model().simulation.method == IntegrationMethod::generalized_alpha) {
    eq = lin.emplace(linearize(rig)).equilibrium.configuration;
  } else {
    const Equilibrium e = static_equilibrium(rig);
    if (!e.converged) throw NoEquilibrium(e.message);
    eq = e.configuration;
  }
  const auto& initial = rig.model().release.initial;
  std::vector<std::vector<Record>> sets(options.sets);
  for (int k = 0; k < options.sets; ++k) {
    for (int j = 0; j < options.histories; ++j) {
      if (options.progress) options.progress(k + 1, j + 1);
      HistoryRequest req;
      req.duration_s = options.duration_s;
      req.noise_seed = noise_seed(options.seed, k + 1, j + 1);
      req.linearization = lin ? &*lin : nullptr;
      RecordComments comments;
      if (!initial.empty()) {
        req.initial = initial[static_cast<size_t>(j) % initial.size()];
        comments.emplace_back("release", "initial condition " + std::to_string(j % initial.size() + 1));
      } else {
        req.push = draw_push(rig, options.seed, k + 1, j + 1);
        const Push& p = *req.push;
        char buf[200];
        std::snprintf(buf, sizeof buf, "raised-cosine push %.6g s, force [%.6g, %.6g, %.6g] N, moment [0, 0, %.6g] N m",
                      p.duration_s, p.force.x(), p.force.y(), p.force.z(), p.moment.z());
        comments.emplace_back("release", buf);
      }
      Record h = simulate_history(rig, eq, req);
      h.provenance.comments = comments;
      sets[k].push_back(std::move(h));
    }
  }
  return sets;
}

}  // namespace rigflex::rig
