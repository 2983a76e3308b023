#include "diagnose/residual_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "diagnose/welch.hpp"

namespace rigflex::diagnose {
namespace {

// Welch amplitude spectral density of x (segments of `n` samples).
Eigen::VectorXd welch(const Eigen::VectorXd& x, int n, double h) {
  const WelchSums w = welch_sums(x, n);
  // One-sided power spectral density, then its square root.
  return (w.power * (2.0 * h / (w.window_power * std::max(w.segments, 1)))).cwiseSqrt();
}

double pearson(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::ArrayXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double d = std::sqrt((x * x).sum() * (y * y).sum());
  return d > 0 ? (x * y).sum() / d : 0.0;
}

Eigen::VectorXd derivative(const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd d(x.size());
  const Eigen::Index n = x.size();
  for (Eigen::Index k = 1; k + 1 < n; ++k) d(k) = (x(k + 1) - x(k - 1)) / (2 * h);
  d(0) = n > 1 ? (x(1) - x(0)) / h : 0.0;
  d(n - 1) = n > 1 ? (x(n - 1) - x(n - 2)) / h : 0.0;
  return d;
}

// Slope of ln(y) against t, y > 0 (least squares); 0 if too few points.
double log_slope(const std::vector<double>& t, const std::vector<double>& y) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  int n = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!(y[i] > 0)) continue;
    const double ly = std::log(y[i]);
    st += t[i], sy += ly, stt += t[i] * t[i], sty += t[i] * ly;
    ++n;
  }
  if (n < 3) return 0.0;
  const double den = n * stt - st * st;
  return den > 0 ? (n * sty - st * sy) / den : 0.0;
}

// Per channel: noise, offsets, whiteness, energy.
void channel_statistics(const std::vector<HistoryComparison>& hs, int C, ResidualAnalysis& a) {
  a.noise = Eigen::VectorXd::Zero(C);
  a.noise_ratio = Eigen::VectorXd::Zero(C);
  a.static_offset = Eigen::VectorXd::Zero(C);
  a.offset_in_noise = Eigen::VectorXd::Zero(C);
  a.lag1 = Eigen::VectorXd::Zero(C);
  a.channel_share = Eigen::VectorXd::Zero(C);
  double samples = 0;
  Eigen::VectorXd sum_r = Eigen::VectorXd::Zero(C), sum_r2 = Eigen::VectorXd::Zero(C), sum_lag = Eigen::VectorXd::Zero(C);
  Eigen::VectorXd energy = Eigen::VectorXd::Zero(C);
  for (const auto& h : hs) {
    const Eigen::MatrixXd r = h.residual();
    samples += static_cast<double>(r.rows());
    a.noise += h.target.sigma / static_cast<double>(hs.size());
    for (int c = 0; c < C; ++c) {
      const Eigen::VectorXd x = r.col(c);
      sum_r(c) += x.sum();
      sum_r2(c) += x.squaredNorm();
      const Eigen::VectorXd xc = x.array() - x.mean();
      sum_lag(c) += xc.head(xc.size() - 1).dot(xc.tail(xc.size() - 1));
      energy(c) += x.squaredNorm() / (h.target.sigma(c) * h.target.sigma(c));
    }
  }
  for (int c = 0; c < C; ++c) {
    a.static_offset(c) = sum_r(c) / samples;
    const double var = sum_r2(c) / samples - a.static_offset(c) * a.static_offset(c);
    a.noise_ratio(c) = std::sqrt(sum_r2(c) / samples) / a.noise(c);
    a.offset_in_noise(c) = a.static_offset(c) / (a.noise(c) / std::sqrt(samples));
    a.lag1(c) = var > 0 ? sum_lag(c) / (var * samples) : 0.0;
  }
  a.channel_share = energy / std::max(energy.sum(), 1e-300);
}

// Trend and windows: one-second windows (at least a swing period).
void windows_and_trend(const std::vector<HistoryComparison>& hs, int C, double longest_period, ResidualAnalysis& a) {
  const double width = std::max(1.0, std::ceil(longest_period));
  double total_energy = 0;
  std::vector<std::pair<double, double>> trend_acc;  // per window index: sum of nrmse^2 terms, count
  for (int j = 0; j < static_cast<int>(hs.size()); ++j) {
    const auto& h = hs[static_cast<size_t>(j)];
    const Eigen::MatrixXd r = h.residual();
    const Eigen::VectorXd& t = h.t();
    Eigen::VectorXd sd(C);
    for (int c = 0; c < C; ++c) {
      const Eigen::VectorXd x = h.measured().col(c);
      sd(c) = std::sqrt((x.array() - x.mean()).square().mean());
    }
    Eigen::Index start = 0;
    for (int w = 0; start < t.size(); ++w) {
      Eigen::Index end = start;
      while (end < t.size() && t(end) - t(start) < width) ++end;
      const auto block = r.middleRows(start, end - start);
      double e = 0, nr = 0;
      for (int c = 0; c < C; ++c) {
        e += block.col(c).squaredNorm() / (h.target.sigma(c) * h.target.sigma(c));
        const double rms = std::sqrt(block.col(c).squaredNorm() / static_cast<double>(block.rows()));
        nr += sd(c) > 0 ? (rms / sd(c)) * (rms / sd(c)) : 0.0;
      }
      total_energy += e;
      a.windows.push_back({j, t(start) - t(0), t(end - 1) - t(0), e});
      if (static_cast<int>(trend_acc.size()) <= w) trend_acc.resize(static_cast<size_t>(w + 1), {0.0, 0.0});
      trend_acc[static_cast<size_t>(w)].first += nr / C;
      trend_acc[static_cast<size_t>(w)].second += 1;
      start = end;
    }
  }
  for (auto& w : a.windows) w.share /= std::max(total_energy, 1e-300);
  std::sort(a.windows.begin(), a.windows.end(), [](const auto& x, const auto& y) { return x.share > y.share; });
  if (a.windows.size() > 8) a.windows.resize(8);
  for (size_t w = 0; w < trend_acc.size(); ++w) {
    a.trend_t.push_back((static_cast<double>(w) + 0.5) * width);
    a.trend_nrmse.push_back(std::sqrt(trend_acc[w].first / trend_acc[w].second));
  }
  {
    const double N = static_cast<double>(a.trend_t.size());
    if (N >= 2) {
      double st = 0, sy = 0, stt = 0, sty = 0;
      for (size_t i = 0; i < a.trend_t.size(); ++i) {
        st += a.trend_t[i], sy += a.trend_nrmse[i], stt += a.trend_t[i] * a.trend_t[i];
        sty += a.trend_t[i] * a.trend_nrmse[i];
      }
      a.trend_slope = (N * sty - st * sy) / (N * stt - st * st);
    }
  }
}

// Decay of the swing envelope, angle channels.
void envelope_decay(const std::vector<HistoryComparison>& hs, int n, double longest_period, ResidualAnalysis& a) {
  const int C = 3 * n;
  double extra = 0;
  for (int j = 0; j < static_cast<int>(hs.size()); ++j) {
    const auto& h = hs[static_cast<size_t>(j)];
    const Eigen::VectorXd& t = h.t();
    std::vector<double> tc, meas, model;
    const double w2 = 2.0 * longest_period;
    for (Eigen::Index start = 0; start < t.size();) {
      Eigen::Index end = start;
      while (end < t.size() && t(end) - t(start) < w2) ++end;
      if (t(end - 1) - t(start) < 0.9 * w2) break;
      double em = 0, eo = 0;
      for (int c = n; c < C; ++c) {
        const Eigen::VectorXd xm = h.measured().col(c).segment(start, end - start);
        const Eigen::VectorXd xo = h.model.col(c).segment(start, end - start);
        em += (xm.array() - xm.mean()).square().mean();
        eo += (xo.array() - xo.mean()).square().mean();
      }
      tc.push_back(0.5 * (t(start) + t(end - 1)));
      meas.push_back(std::sqrt(em));
      model.push_back(std::sqrt(eo));
      start = end;
    }
    DecayComparison d;
    d.history = j;
    d.measured_rate = -log_slope(tc, meas);
    d.model_rate = -log_slope(tc, model);
    extra += (d.measured_rate - d.model_rate) / static_cast<double>(hs.size());
    a.decay.push_back(d);
  }
  a.extra_decay_rate = extra;
}

// Spectra: segments of about 8 s (a power of two, the record's length at
// most), on the first record's frequency axis; a record at another rate
// has its own segments, its spectrum interpolated onto that axis.
void residual_spectra(const std::vector<HistoryComparison>& hs, int n, double highest_swing, ResidualAnalysis& a) {
  const int C = 3 * n;
  auto segment_for = [](double step, Eigen::Index length) {
    int seg = 16;
    while (seg * 2 <= length && seg * 2 * step <= 8.0 + 1e-9) seg *= 2;
    return seg;
  };
  const double h = hs.front().target.record.step_s;
  const int seg = segment_for(h, hs.front().t().size());
  const int bins = seg / 2 + 1;
  auto& s = a.spectra;
  s.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 0.0, 0.5 / h);
  s.residual_force = s.residual_angle = s.measured_force = s.measured_angle = Eigen::VectorXd::Zero(bins);
  auto onto_axis = [&](const Eigen::VectorXd& psd, double step, int own_seg) {
    if (own_seg == seg && step == h) return psd;
    Eigen::VectorXd out(bins);
    const double df = 1.0 / (own_seg * step);
    for (int k = 0; k < bins; ++k) {
      const double x = s.frequency_hz(k) / df;
      const int i = std::min(static_cast<int>(x), static_cast<int>(psd.size()) - 2);
      const double w = std::clamp(x - i, 0.0, 1.0);
      out(k) = x > psd.size() - 1 ? 0.0 : (1 - w) * psd(i) + w * psd(i + 1);
    }
    return out;
  };
  for (const auto& x : hs) {
    const double hx = x.target.record.step_s;
    const int sx = segment_for(hx, x.t().size());
    const Eigen::MatrixXd r = x.residual();
    for (int c = 0; c < C; ++c) {
      const bool force = c < n;
      const double norm = 1.0 / (static_cast<double>(hs.size()) * (force ? n : 2 * n));
      (force ? s.residual_force : s.residual_angle) += norm * onto_axis(welch(r.col(c), sx, hx), hx, sx);
      (force ? s.measured_force : s.measured_angle) += norm * onto_axis(welch(x.measured().col(c), sx, hx), hx, sx);
    }
  }
  auto peaks = [&](const Eigen::VectorXd& psd, const std::string& group) {
    std::vector<SpectrumPeak> found;
    const double fmax = std::max(5.0 * std::max(highest_swing, 0.5), 10.0);
    for (int k = 1; k + 1 < bins; ++k) {
      if (s.frequency_hz(k) > fmax) break;
      if (psd(k) > psd(k - 1) && psd(k) >= psd(k + 1)) {
        SpectrumPeak p{group, s.frequency_hz(k), psd(k), 0.0};
        double best = INFINITY;
        for (double f : a.mode_frequencies_hz) {
          if (std::abs(f - p.frequency_hz) < best) best = std::abs(f - p.frequency_hz), p.nearest_mode_hz = f;
        }
        found.push_back(p);
      }
    }
    std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.amplitude > y.amplitude; });
    if (found.size() > 3) found.resize(3);
    s.peaks.insert(s.peaks.end(), found.begin(), found.end());
  };
  peaks(s.residual_force, "force");
  peaks(s.residual_angle, "angle");
}

// Correlation of each channel's residual with the states of its rod (from
// the model: noise-free), pooled over the histories.
void state_correlations(const std::vector<HistoryComparison>& hs, int n, ResidualAnalysis& a) {
  const int C = 3 * n;
  const char* names[] = {"angle", "velocity", "sign_of_velocity", "acceleration", "rod_force"};
  for (int k = 0; k < 5; ++k) a.correlations.push_back({names[k], 0.0, "", Eigen::VectorXd::Zero(C)});
  for (int c = 0; c < C; ++c) {
    const int rod = c % n;
    std::vector<Eigen::VectorXd> res, st[5];
    Eigen::Index total = 0;
    for (const auto& x : hs) {
      // The rod's angle channel that swings most (alpha or beta) stands for it on the force channel.
      int angle = c >= n ? c : n + rod;
      if (c < n) {
        const Eigen::VectorXd al = x.model.col(n + rod), be = x.model.col(2 * n + rod);
        if ((be.array() - be.mean()).square().sum() > (al.array() - al.mean()).square().sum()) angle = 2 * n + rod;
      }
      const double hx = x.target.record.step_s;
      const Eigen::VectorXd th = x.model.col(angle);
      const Eigen::VectorXd v = derivative(th, hx);
      res.push_back(x.residual().col(c));
      st[0].push_back(th);
      st[1].push_back(v);
      st[2].push_back(v.array().sign().matrix());
      st[3].push_back(derivative(v, hx));
      st[4].push_back(x.model.col(rod));
      total += x.t().size();
    }
    auto stack = [&](const std::vector<Eigen::VectorXd>& parts) {
      Eigen::VectorXd all(total);
      Eigen::Index at = 0;
      for (const auto& p : parts) all.segment(at, p.size()) = p, at += p.size();
      return all;
    };
    const Eigen::VectorXd rall = stack(res);
    for (int k = 0; k < 5; ++k) {
      const double r = pearson(rall, stack(st[k]));
      a.correlations[static_cast<size_t>(k)].per_channel(c) = r;
      if (std::abs(r) > std::abs(a.correlations[static_cast<size_t>(k)].largest)) {
        a.correlations[static_cast<size_t>(k)].largest = r;
        a.correlations[static_cast<size_t>(k)].channel = a.channels[static_cast<size_t>(c)];
      }
    }
  }
}

}  // namespace

ResidualAnalysis analyse_residuals(const ResponseModel& m, const std::vector<HistoryComparison>& hs) {
  ResidualAnalysis a;
  if (hs.empty()) return a;
  const int n = m.system.rods();
  const int C = 3 * n;
  a.channels = channel_names(n);
  double longest_period = 0, highest_swing = 0;
  for (const auto& mode : m.linearization.modes) {
    a.mode_frequencies_hz.push_back(mode.frequency_hz);
    a.mode_kinds.push_back(to_string(mode.kind));
    if (mode.kind == rig::RigModeKind::swing && mode.frequency_hz > 0) {
      longest_period = std::max(longest_period, 1.0 / mode.frequency_hz);
      highest_swing = std::max(highest_swing, mode.frequency_hz);
    }
  }
  if (longest_period <= 0) longest_period = 2.0;
  channel_statistics(hs, C, a);
  windows_and_trend(hs, C, longest_period, a);
  envelope_decay(hs, n, longest_period, a);
  residual_spectra(hs, n, highest_swing, a);
  state_correlations(hs, n, a);
  return a;
}

}  // namespace rigflex::diagnose
