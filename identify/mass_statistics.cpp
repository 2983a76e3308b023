#include "identify/mass_statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace rigflex::identify {

namespace {

void require(bool ok, const char* message) {
  if (!ok) throw std::invalid_argument(message);
}

bool all_finite(const std::vector<double>& x) {
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

struct Moments {
  double mean = 0;
  double variance = 0;  // n - 1 in the denominator; 0 for a single value
};

// Two passes: the one-pass sum of squares cancels badly for the small
// scatter of repeated identifications around a large mean.
Moments moments(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  Moments m;
  m.mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
  if (x.size() < 2) return m;
  double ss = 0;
  for (double v : x) ss += (v - m.mean) * (v - m.mean);
  m.variance = ss / (n - 1);
  return m;
}

using Column = std::vector<double>;

std::array<Column, 9> component_columns(const std::vector<fe::MassProperties>& sets) {
  std::array<Column, 9> columns;
  for (Column& c : columns) c.reserve(sets.size());
  for (const fe::MassProperties& p : sets) {
    const std::array<double, 9> c = mass_components(p);
    for (std::size_t k = 0; k < 9; ++k) columns[k].push_back(c[k]);
  }
  return columns;
}

// Inclusive: the limits are decimal fractions and the deviation a difference
// of rounded numbers, so a deviation exactly at the limit on paper (0.103 m
// against 0.100 m with 3 mm) can land a few ulps outside; the slack covers
// that and nothing a measurement could resolve.
bool within(double value, double reference, double limit) {
  constexpr double slack = 16 * std::numeric_limits<double>::epsilon();
  return std::isfinite(value) &&
         std::abs(value - reference) <= limit + slack * (std::abs(value) + std::abs(reference) + limit);
}

}  // namespace

std::array<double, 9> mass_components(const fe::MassProperties& p) {
  const Eigen::Matrix3d& J = p.inertia;
  return {p.cog.x(), p.cog.y(), p.cog.z(), J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2)};
}

const std::array<const char*, 9>& mass_component_names() {
  static const std::array<const char*, 9> names = {"xG", "yG", "zG", "Jxx", "Jyy", "Jzz", "Jxy", "Jxz", "Jyz"};
  return names;
}

SampleSummary summarize(const std::vector<double>& x, double confidence) {
  require(!x.empty(), "summarize: no values");
  require(confidence > 0 && confidence < 1, "summarize: confidence must be in (0, 1)");
  require(all_finite(x), "summarize: non-finite value");
  const Moments m = moments(x);
  SampleSummary s;
  s.count = static_cast<int>(x.size());
  s.mean = m.mean;
  if (s.count < 2) return s;
  s.std = std::sqrt(m.variance);
  const boost::math::students_t_distribution<double> t(s.count - 1);
  // The upper quantile taken from the complement keeps its accuracy for
  // confidences close to 1.
  const double t_upper = boost::math::quantile(boost::math::complement(t, (1 - confidence) / 2));
  const double half = t_upper * *s.std / std::sqrt(static_cast<double>(s.count));
  s.confidence_interval = std::array<double, 2>{s.mean - half, s.mean + half};
  return s;
}

WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b, double alpha) {
  require(a.size() >= 2 && b.size() >= 2, "welch_t_test: each sample needs at least 2 values");
  require(all_finite(a) && all_finite(b), "welch_t_test: non-finite value");
  require(alpha > 0 && alpha < 1, "welch_t_test: alpha must be in (0, 1)");
  const Moments ma = moments(a), mb = moments(b);
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  const double va = ma.variance / na, vb = mb.variance / nb;
  const double difference = ma.mean - mb.mean;
  WelchTest w;
  if (va + vb == 0) {
    // Welch-Satterthwaite is 0/0 here; with both variances equal (zero) the
    // pooled test's degrees of freedom are the natural value.
    w.degrees_of_freedom = na + nb - 2;
    if (difference != 0) {
      w.t = std::copysign(std::numeric_limits<double>::infinity(), difference);
      w.p_value = 0;
    }
  } else {
    const double se2 = va + vb;
    w.t = difference / std::sqrt(se2);
    // In shares of se2, so that tiny variances cannot underflow when squared.
    const double wa = va / se2, wb = vb / se2;
    w.degrees_of_freedom = 1 / (wa * wa / (na - 1) + wb * wb / (nb - 1));
    const boost::math::students_t_distribution<double> t(w.degrees_of_freedom);
    w.p_value = 2 * boost::math::cdf(boost::math::complement(t, std::abs(w.t)));
  }
  w.significant = w.p_value < alpha;
  return w;
}

MassSummary summarize(const std::vector<fe::MassProperties>& sets, double confidence) {
  Column mass;
  mass.reserve(sets.size());
  for (const fe::MassProperties& p : sets) mass.push_back(p.mass);
  MassSummary s;
  s.mass = summarize(mass, confidence);
  const std::array<Column, 9> columns = component_columns(sets);
  for (std::size_t k = 0; k < 9; ++k) s.components[k] = summarize(columns[k], confidence);
  return s;
}

std::array<WelchTest, 9> compare_algorithms(const std::vector<fe::MassProperties>& a,
                                            const std::vector<fe::MassProperties>& b, double alpha) {
  const std::array<Column, 9> ca = component_columns(a), cb = component_columns(b);
  std::array<WelchTest, 9> tests;
  for (std::size_t k = 0; k < 9; ++k) tests[k] = welch_t_test(ca[k], cb[k], alpha);
  return tests;
}

void AccuracyLimits::validate() const {
  for (double limit : {moment_relative, product_of_largest, cog_in_plane_m, cog_height_m})
    require(std::isfinite(limit) && limit >= 0, "AccuracyLimits: each limit must be finite and >= 0");
}

AccuracyShare share_within_accuracy(const std::vector<fe::MassProperties>& sets, const fe::MassProperties& reference,
                                    const AccuracyLimits& limits) {
  limits.validate();
  require(!sets.empty(), "share_within_accuracy: no sets");
  const std::array<double, 9> r = mass_components(reference);
  require(std::all_of(r.begin(), r.end(), [](double v) { return std::isfinite(v); }),
          "share_within_accuracy: non-finite reference");

  const double largest = std::max({std::abs(r[3]), std::abs(r[4]), std::abs(r[5])});
  const double product = limits.product_of_largest * largest;
  const std::array<double, 9> limit = {limits.cog_in_plane_m,
                                       limits.cog_in_plane_m,
                                       limits.cog_height_m,
                                       limits.moment_relative * std::abs(r[3]),
                                       limits.moment_relative * std::abs(r[4]),
                                       limits.moment_relative * std::abs(r[5]),
                                       product,
                                       product,
                                       product};

  std::array<int, 9> inside{};
  int all_inside = 0;
  for (const fe::MassProperties& p : sets) {
    const std::array<double, 9> c = mass_components(p);
    bool all = true;
    for (std::size_t k = 0; k < 9; ++k) {
      const bool ok = within(c[k], r[k], limit[k]);
      inside[k] += ok;
      all = all && ok;
    }
    all_inside += all;
  }

  const double n = static_cast<double>(sets.size());
  AccuracyShare share;
  for (std::size_t k = 0; k < 9; ++k) share.component[k] = inside[k] / n;
  share.all = all_inside / n;
  return share;
}

std::vector<NormalProbabilityPoint> normal_probability(std::vector<double> values) {
  require(all_finite(values), "normal_probability: non-finite value");
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  const boost::math::normal_distribution<double> standard;
  std::vector<NormalProbabilityPoint> points;
  points.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double p = (static_cast<double>(i + 1) - 0.375) / (n + 0.25);
    points.push_back({values[i], p, boost::math::quantile(standard, p)});
  }
  return points;
}

std::vector<OrderStatisticBand> normal_order_statistic_band(std::size_t n, double sigmas) {
  require(sigmas > 0 && std::isfinite(sigmas), "normal_order_statistic_band: sigmas must be positive");
  const boost::math::normal_distribution<double> standard;
  const double tail = boost::math::cdf(standard, -sigmas);  // each side
  std::vector<OrderStatisticBand> band;
  band.reserve(n);
  for (std::size_t i = 1; i <= n; ++i) {
    const boost::math::beta_distribution<double> rank(static_cast<double>(i), static_cast<double>(n + 1 - i));
    band.push_back({boost::math::quantile(standard, boost::math::quantile(rank, tail)),
                    boost::math::quantile(standard, boost::math::quantile(rank, 1.0 - tail))});
  }
  return band;
}

}  // namespace rigflex::identify
