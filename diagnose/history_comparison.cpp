#include "diagnose/history_comparison.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "diagnose/band_noise.hpp"
#include "identify/identification_kinematics.hpp"
#include "rig/encoder.hpp"
#include "rig/equilibrium.hpp"
#include "rig/median.hpp"
#include "rig/pose_fit.hpp"

namespace rigflex::diagnose {

void CompareOptions::validate() const {
  if (!(fit_window_s > 0)) throw std::invalid_argument("fit_window_s: must be positive");
  if (max_iterations < 1) throw std::invalid_argument("max_iterations: must be at least 1");
}

namespace {

double std_dev(const Eigen::VectorXd& x) {
  if (x.size() < 2) return 0.0;
  return std::sqrt((x.array() - x.mean()).square().sum() / static_cast<double>(x.size() - 1));
}

double highest_swing_hz(const ResponseModel& m) {
  double f = 0;
  for (const auto& mode : m.linearization.modes) {
    if (mode.kind == rig::RigModeKind::swing) f = std::max(f, mode.frequency_hz);
  }
  return f;
}

// Typical size of the state coordinates: steps for the finite differences
// and the scale of Levenberg-Marquardt's convergence test.
SwingState state_scale(const ResponseModel& m) {
  double L = 0;
  for (const auto& r : m.system.assembly().geometry.rods) L += r.length;
  L /= m.system.rods();
  double w = 2.0 * std::numbers::pi * 0.5;
  for (const auto& mode : m.linearization.modes) {
    if (mode.kind == rig::RigModeKind::swing) {
      w = 2.0 * std::numbers::pi * mode.frequency_hz;
      break;
    }
  }
  SwingState s;
  s << 0.05 * L, 0.05 * L, 0.05, 0.05 * L * w, 0.05 * L * w, 0.05 * w;
  return s;
}

}  // namespace

Eigen::VectorXd channel_noise(const Eigen::MatrixXd& channels) {
  Eigen::VectorXd sigma(channels.cols());
  for (Eigen::Index c = 0; c < channels.cols(); ++c) {
    const Eigen::VectorXd x = channels.col(c);
    std::vector<double> d3;
    d3.reserve(static_cast<size_t>(std::max<Eigen::Index>(x.size() - 3, 0)));
    for (Eigen::Index k = 0; k + 3 < x.size(); ++k) d3.push_back(std::abs(x(k + 3) - 3 * x(k + 2) + 3 * x(k + 1) - x(k)));
    const double mad = rig::upper_median(d3);
    // Quantized data (an encoder of few bits against a slow swing) can make
    // most third differences exactly zero: the quantization noise, step /
    // sqrt(12) with the step the smallest nonzero change between samples,
    // is then the floor; with no median either, the RMS of the differences.
    double quantum = INFINITY, sum2 = 0;
    for (Eigen::Index k = 0; k + 1 < x.size(); ++k) {
      const double dx = std::abs(x(k + 1) - x(k));
      if (dx > 0) quantum = std::min(quantum, dx);
    }
    for (double v : d3) sum2 += v * v;
    double s = 1.4826 * mad / std::sqrt(20.0);
    if (std::isfinite(quantum)) s = std::max(s, quantum / std::sqrt(12.0));
    if (s <= 0 && !d3.empty()) s = std::sqrt(sum2 / static_cast<double>(d3.size()) / 20.0);
    const double scale = std::max(x.cwiseAbs().maxCoeff(), 1e-300);
    sigma(c) = std::max(s, 1e-9 * scale);
  }
  return sigma;
}

Eigen::Index BandTarget::rows_within(double seconds) const {
  Eigen::Index r = 0;
  while (r < static_cast<Eigen::Index>(at.size()) && record.t(at[static_cast<size_t>(r)]) - record.t(0) <= seconds) ++r;
  return std::max<Eigen::Index>(r, std::min<Eigen::Index>(static_cast<Eigen::Index>(at.size()), 8));
}

BandTarget band_target(const ResponseModel& m, const rig::Record& record) {
  BandTarget b;
  b.record = uniform_record(record.t, channels_of(record));
  b.band = swing_band(b.record.step_s, highest_swing_hz(m));
  b.sigma = band_noise(channel_noise(b.record.channels), near_band_noise(b.record.channels, b.band));
  b.at = band_samples(b.band, b.record.t.size());
  if (b.at.size() < 8) {
    // The band filter spans half_width samples on each side of every
    // compared one, and the comparison needs eight of them.
    const double needed = (2.0 * b.band.half_width() + 8.0 * b.band.decimation) * b.record.step_s;
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "the record is too short for the swing band: %.4g s, where the band's filter needs at least "
                  "%.3g s",
                  b.record.t(b.record.t.size() - 1) - b.record.t(0), needed);
    throw std::invalid_argument(msg);
  }
  b.measured = band_filter(b.band, b.record.channels, b.at);
  b.weight = (b.sigma * b.band.noise_gain()).cwiseInverse();
  return b;
}

Eigen::VectorXd band_residual(const ResponseModel& m, const SwingState& s, const BandTarget& target,
                              Eigen::Index rows) {
  if (rows < 0 || rows > static_cast<Eigen::Index>(target.at.size())) rows = static_cast<Eigen::Index>(target.at.size());
  const std::vector<Eigen::Index> at(target.at.begin(), target.at.begin() + rows);
  const Eigen::Index needed = at.back() + target.band.half_width() + 1;
  const Eigen::MatrixXd model = predict_channels(m, s, target.record.t.head(needed));
  Eigen::MatrixXd r = (target.measured.topRows(rows) - band_filter(target.band, model, at)) * target.weight.asDiagonal();
  return Eigen::Map<Eigen::VectorXd>(r.data(), r.size());
}

SwingFit fit_swing_state(const ResponseModel& m, const BandTarget& target, const SwingState& guess,
                         const CompareOptions& options) {
  options.validate();
  const Eigen::Index rows = target.rows_within(options.fit_window_s);
  const SwingState scale = state_scale(m);
  auto residual = [&](const SwingState& s) { return band_residual(m, s, target, rows); };

  SwingFit fit;
  fit.state = guess;
  Eigen::VectorXd r = residual(fit.state);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  for (int it = 0; it < options.max_iterations; ++it) {
    fit.iterations = it + 1;
    // Forward differences at 1e-4 of each coordinate's typical size: the
    // response is smooth and nearly linear at swing amplitudes.
    Eigen::MatrixXd J(r.size(), 6);
    for (int j = 0; j < 6; ++j) {
      SwingState sp = fit.state;
      const double h = 1e-4 * scale(j);
      sp(j) += h;
      J.col(j) = (residual(sp) - r) / h;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false, any_evaluated = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12 * JtJ.diagonal().maxCoeff());
      const SwingState step = -A.ldlt().solve(g);
      const SwingState trial = fit.state + step;
      Eigen::VectorXd r_trial;
      try {
        r_trial = residual(trial);
      } catch (const std::exception&) {
        lambda *= 10;  // a state the rig cannot hold: shorten the step
        continue;
      }
      any_evaluated = true;
      const double c_trial = r_trial.squaredNorm();
      if (c_trial < cost) {
        const double drop = (cost - c_trial) / cost;
        fit.state = trial;
        r = r_trial;
        cost = c_trial;
        lambda = std::max(lambda / 10, 1e-9);
        improved = true;
        if (drop < 1e-8 || step.cwiseQuotient(scale).cwiseAbs().maxCoeff() < 1e-7) fit.converged = true;
      } else {
        lambda *= 10;
      }
    }
    // No descent left at any damping: a minimum to working precision (not
    // when every trial state was one the rig could not hold).
    if (!improved) fit.converged = any_evaluated;
    if (!improved) break;
    if (fit.converged) break;
  }
  fit.whitened_rms = std::sqrt(cost / static_cast<double>(r.size()));
  return fit;
}

double rms_of(const Eigen::VectorXd& per_channel, Eigen::Index first, Eigen::Index count) {
  return std::sqrt(per_channel.segment(first, count).squaredNorm() / static_cast<double>(count));
}

Eigen::VectorXd nrmse_of(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& model) {
  Eigen::VectorXd e(measured.cols());
  for (Eigen::Index c = 0; c < measured.cols(); ++c) {
    const double rms = std::sqrt((measured.col(c) - model.col(c)).squaredNorm() / static_cast<double>(measured.rows()));
    const double sd = std_dev(measured.col(c));
    e(c) = sd > 0 ? rms / sd : (rms > 0 ? INFINITY : 0.0);
  }
  return e;
}

ElasticState fit_elastic_state(const ResponseModel& m, const BandTarget& target, const SwingState& s,
                               double window_s) {
  const int q = static_cast<int>(m.elastic_modes.size());
  if (q == 0) return {};
  Eigen::Index count = 0;
  const Eigen::VectorXd& t = target.record.t;
  while (count < t.size() && t(count) - t(0) <= window_s) ++count;
  count = std::max<Eigen::Index>(count, std::min<Eigen::Index>(t.size(), 8));
  const Eigen::VectorXd tw = t.head(count);
  const Eigen::VectorXd w = target.sigma.cwiseInverse();
  auto residual = [&](const ElasticState& e) {
    Eigen::MatrixXd r = (target.record.channels.topRows(count) - predict_channels(m, s, tw, e)) * w.asDiagonal();
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(r.data(), r.size()));
  };
  ElasticState zero{Eigen::VectorXd::Zero(q), Eigen::VectorXd::Zero(q)};
  const Eigen::VectorXd r0 = residual(zero);
  // Forward differences: each mode's amplitude and rate by a step that
  // moves its largest coordinate by 1e-6 (m or rad); the response is linear.
  Eigen::MatrixXd J(r0.size(), 2 * q);
  Eigen::VectorXd step(2 * q);
  for (int k = 0; k < q; ++k) {
    const rig::RigMode& mode = m.linearization.modes[static_cast<size_t>(m.elastic_modes[static_cast<size_t>(k)])];
    const double a = 1e-6 / std::max(mode.shape.cwiseAbs().maxCoeff(), 1e-300);
    step(k) = a;
    step(q + k) = a * 2.0 * std::numbers::pi * mode.frequency_hz;
  }
  for (int j = 0; j < 2 * q; ++j) {
    ElasticState e = zero;
    (j < q ? e.amplitude(j) : e.rate(j - q)) = step(j);
    J.col(j) = (r0 - residual(e)) / step(j);
  }
  const Eigen::VectorXd x = J.completeOrthogonalDecomposition().solve(r0);
  ElasticState fitted{x.head(q), x.tail(q)};
  try {
    if (residual(fitted).squaredNorm() < r0.squaredNorm()) return fitted;
  } catch (const std::exception&) {
    // An elastic state the integrator cannot start from: the frames start settled.
  }
  return zero;
}

void check_record_fits_rig(const ResponseModel& m, const Eigen::VectorXd& t, const Eigen::MatrixXd& channels) {
  const int n = m.system.rods();
  const rig::RigGeometry& g = m.system.assembly().geometry;
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    for (int i = 0; i < n; ++i) {
      for (int which = 0; which < 2; ++which) {
        const double a = channels(k, (1 + which) * n + i);
        if (!(std::abs(a) < 0.5 * std::numbers::pi)) {
          throw rig::RecordError(static_cast<long>(k), (which ? "beta" : "alpha") + std::to_string(i + 1),
                            "an encoder angle of " + std::to_string(a) +
                                " rad turns the rod above its joint: impossible for a hanging rod (units rad?)");
        }
      }
    }
  }
  // The lower joints the encoders give must form the carrying frame's joint
  // pattern: a wrong rod order or encoder axis, or degrees, break it.
  rig::JointPoints body(3, n), world(3, n);
  for (int i = 0; i < n; ++i) body.col(i) = g.rods[static_cast<size_t>(i)].lower;
  double radius = 0;
  for (int i = 0; i < n; ++i) radius = std::max(radius, (body.col(i) - body.rowwise().mean()).norm());
  const double limit = std::max(0.02, 0.05 * radius);
  const Eigen::Index step = std::max<Eigen::Index>(1, t.size() / 50);
  for (Eigen::Index k = 0; k < t.size(); k += step) {
    for (int i = 0; i < n; ++i) {
      const rig::RodGeometry& rod = g.rods[static_cast<size_t>(i)];
      world.col(i) = rod.upper + rod.length * rig::rod_direction(rod.encoder_axis, {channels(k, n + i), channels(k, 2 * n + i)});
    }
    const rig::PoseFit p = rig::fit_pose(body, world);
    if (p.rms_residual > limit) {
      throw rig::RecordError(static_cast<long>(k), "",
                        "the encoder angles put the lower joints " + std::to_string(1e3 * p.rms_residual) +
                            " mm (RMS) away from the carrying frame's joint pattern: check the rod order, the "
                            "encoder axes and the angle units against the rig file");
    }
  }
}

HistoryComparison compare_history(const ResponseModel& m, const rig::Record& record, const std::string& source,
                                  const CompareOptions& options) {
  options.validate();
  if (record.force.cols() != m.system.rods()) {
    throw std::invalid_argument(source + ": " + std::to_string(record.force.cols()) + " load cells, the rig has " +
                                std::to_string(m.system.rods()) + " rods");
  }
  check_record_fits_rig(m, record.t, channels_of(record));
  HistoryComparison h;
  h.source = source;
  try {
    h.target = band_target(m, record);
  } catch (const rig::RecordError&) {
    throw;  // names its sample and channel; the command maps it to the file
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source.empty() ? std::string(e.what()) : source + ": " + e.what());
  }
  // The encoders' guess may be a state the rig cannot hold (a record that
  // fits the rig badly): then from rest, else the record is named.
  try {
    h.fit = fit_swing_state(m, h.target, swing_state_from_encoders(m, h.t(), h.measured()), options);
  } catch (const rig::NoEquilibrium&) {
    try {
      h.fit = fit_swing_state(m, h.target, SwingState::Zero(), options);
    } catch (const rig::NoEquilibrium& e) {
      throw std::invalid_argument(source + ": no swing state of the rig starts this record (" + e.what() +
                                  "): check the record against the rig file");
    }
  }
  h.elastic = fit_elastic_state(m, h.target, h.fit.state, options.fit_window_s);
  h.model = predict_channels(m, h.fit.state, h.t(), h.elastic);
  h.band_model = band_filter(h.target.band, h.model, h.target.at);
  h.nrmse = nrmse_of(h.target.measured, h.band_model);
  h.raw_nrmse = nrmse_of(h.measured(), h.model);
  const Eigen::Index rows = h.target.rows_within(options.fit_window_s);
  const Eigen::VectorXd head = nrmse_of(h.target.measured.topRows(rows), h.band_model.topRows(rows));
  h.fit_window_nrmse = rms_of(head, 0, head.size());
  return h;
}

Eigen::VectorXd pooled_nrmse(const std::vector<HistoryComparison>& hs, bool raw) {
  if (hs.empty()) return {};
  const Eigen::Index channels = hs.front().measured().cols();
  Eigen::VectorXd res2 = Eigen::VectorXd::Zero(channels), var = Eigen::VectorXd::Zero(channels);
  for (const auto& h : hs) {
    const Eigen::MatrixXd& y = raw ? h.measured() : h.target.measured;
    const Eigen::MatrixXd& f = raw ? h.model : h.band_model;
    for (Eigen::Index c = 0; c < channels; ++c) {
      res2(c) += (y.col(c) - f.col(c)).squaredNorm();
      var(c) += (y.col(c).array() - y.col(c).mean()).square().sum();
    }
  }
  Eigen::VectorXd e(channels);
  for (Eigen::Index c = 0; c < channels; ++c) {
    e(c) = var(c) > 0 ? std::sqrt(res2(c) / var(c)) : (res2(c) > 0 ? INFINITY : 0.0);  // as nrmse_of
  }
  return e;
}

}  // namespace rigflex::diagnose
