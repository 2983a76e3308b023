// Statistics of repeated mass-properties identifications against hand-worked
// values, published tables and worked examples, and closed forms of the t
// distribution for 1 and 2 degrees of freedom.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "identify/mass_statistics.hpp"


using namespace rigflex::identify;
using rigflex::fe::MassProperties;

namespace {

// A record from the nine components in the order xG, yG, zG, Jxx, Jyy, Jzz, Jxy, Jxz, Jyz.
MassProperties record(double mass, const std::array<double, 9>& c) {
  MassProperties p;
  p.mass = mass;
  p.cog = Eigen::Vector3d(c[0], c[1], c[2]);
  p.inertia << c[3], c[6], c[7],  //
      c[6], c[4], c[8],           //
      c[7], c[8], c[5];
  return p;
}

double half_width(const SampleSummary& s) {
  return ((*s.confidence_interval)[1] - (*s.confidence_interval)[0]) / 2;
}

// Two-sided p of Student's t with 2 degrees of freedom, from its closed-form
// CDF F(t) = 1/2 + t / (2 sqrt(2 + t^2)).
double p_two_dof(double t) { return 1 - std::abs(t) / std::sqrt(2 + t * t); }

}  // namespace

TEST(MassStatistics, ComponentsInOrderWithNames) {
  const std::array<double, 9> c = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ(mass_components(record(10, c)), c);
  const auto& names = mass_component_names();
  const std::array<std::string, 9> expected = {"xG", "yG", "zG", "Jxx", "Jyy", "Jzz", "Jxy", "Jxz", "Jyz"};
  for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(names[k], expected[k]);
  EXPECT_EQ(&mass_component_names(), &names);  // one table, not a fresh copy per call
}

TEST(MassStatisticsSummary, HandComputedSampleWithTableQuantiles) {
  // Mean 10.0, squared deviations 0.01 + 0.04 + 0.09 + 0 + 0.04 = 0.18, s^2 = 0.18 / 4 = 0.045,
  // standard error sqrt(0.045 / 5) = sqrt(0.009).
  const std::vector<double> x = {10.1, 9.8, 10.3, 10.0, 9.8};
  const double se = std::sqrt(0.009);
  const SampleSummary s = summarize(x);
  EXPECT_EQ(s.count, 5);
  EXPECT_NEAR(s.mean, 10.0, 1e-13);
  ASSERT_TRUE(s.std.has_value());
  EXPECT_NEAR(*s.std, std::sqrt(0.045), 1e-13);
  ASSERT_TRUE(s.confidence_interval.has_value());
  // t(0.975, 4) = 2.7764 from a published two-sided t table (5 significant digits; NIST/SEMATECH
  // e-Handbook table 1.3.6.7.2 prints 2.776): tolerance half a unit of the last digit times se.
  EXPECT_NEAR(half_width(s), 2.7764 * se, 0.5e-4 * se);
  EXPECT_NEAR((*s.confidence_interval)[0] + (*s.confidence_interval)[1], 2 * 10.0, 1e-12);  // symmetric about the mean
  // t(0.995, 4) = 4.604 and t(0.95, 4) = 2.132 from the same table (4 significant digits).
  EXPECT_NEAR(half_width(summarize(x, 0.99)), 4.604 * se, 0.5e-3 * se);
  EXPECT_NEAR(half_width(summarize(x, 0.90)), 2.132 * se, 0.5e-3 * se);
}

TEST(MassStatisticsSummary, OneAndTwoDegreesOfFreedomClosedForms) {
  // 1 degree of freedom (Cauchy): t(p) = tan(pi (p - 1/2)). {0, 1}: mean 0.5, s = sqrt(0.5), se = 0.5.
  const SampleSummary two = summarize({0.0, 1.0});
  EXPECT_NEAR(*two.std, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(half_width(two), std::tan(std::numbers::pi * 0.475) * 0.5, 1e-11);  // t = 12.7062
  // 2 degrees of freedom: t(p) = (2p - 1) / sqrt(2 p (1 - p)) = 4.302653 for p = 0.975.
  // {1, 2, 6}: mean 3, s^2 = (4 + 1 + 9) / 2 = 7, se = sqrt(7 / 3).
  const SampleSummary three = summarize({1.0, 2.0, 6.0});
  EXPECT_NEAR(three.mean, 3.0, 1e-15);
  EXPECT_NEAR(*three.std, std::sqrt(7.0), 1e-14);
  const double t2 = 0.95 / std::sqrt(2 * 0.975 * 0.025);
  EXPECT_NEAR(t2, 4.302653, 1e-6);  // the printed table value, as a check of the formula
  EXPECT_NEAR(half_width(three), t2 * std::sqrt(7.0 / 3.0), 1e-12);
}

TEST(MassStatisticsSummary, SingleValueHasNoSpread) {
  const SampleSummary s = summarize(std::vector<double>{42.5});  // a bare {42.5} could also be one record
  EXPECT_EQ(s.count, 1);
  EXPECT_EQ(s.mean, 42.5);
  EXPECT_FALSE(s.std.has_value());
  EXPECT_FALSE(s.confidence_interval.has_value());
}

TEST(MassStatisticsSummary, ErrorCases) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(summarize(std::vector<double>{}), std::invalid_argument);
  for (double c : {0.0, 1.0, -0.5, 1.5, nan}) EXPECT_THROW(summarize({1.0, 2.0}, c), std::invalid_argument);
  EXPECT_THROW(summarize({1.0, nan}), std::invalid_argument);
  EXPECT_THROW(summarize({inf, 1.0}), std::invalid_argument);
  EXPECT_THROW(summarize(std::vector<MassProperties>{}), std::invalid_argument);
}

TEST(MassStatisticsWelch, WikipediaWorkedExample) {
  // Wikipedia, "Student's t-test", section "Worked examples" (weights of screws from two machines),
  // unequal variances: standard error 0.04849, d.f. 7.031, t 1.959, two-tailed p 0.09077.
  // Tolerances: half a unit of the last printed digit.
  const std::vector<double> a = {30.02, 29.99, 30.11, 29.97, 30.01, 29.99};
  const std::vector<double> b = {29.89, 29.93, 29.72, 29.98, 30.02, 29.98};
  const WelchTest w = welch_t_test(a, b);
  EXPECT_NEAR(w.t, 1.959, 0.5e-3);
  EXPECT_NEAR(0.095 / w.t, 0.04849, 0.5e-5);
  EXPECT_NEAR(w.degrees_of_freedom, 7.031, 0.5e-3);
  EXPECT_NEAR(w.p_value, 0.09077, 0.5e-5);
  EXPECT_FALSE(w.significant);
  EXPECT_TRUE(welch_t_test(a, b, 0.1).significant);
  // Swapping the samples flips t only.
  const WelchTest r = welch_t_test(b, a);
  EXPECT_DOUBLE_EQ(r.t, -w.t);
  EXPECT_DOUBLE_EQ(r.degrees_of_freedom, w.degrees_of_freedom);
  EXPECT_DOUBLE_EQ(r.p_value, w.p_value);
}

TEST(MassStatisticsWelch, ClosedFormsForOneAndTwoDegreesOfFreedom) {
  // {1, 3} against {4, 6}: equal variances 2, equal sizes 2, so Welch-Satterthwaite gives
  // (1 + 1)^2 / (1 + 1) = 2; t = (2 - 5) / sqrt(2 / 2 + 2 / 2) = -3 / sqrt(2), t^2 = 9/2,
  // p = 1 - sqrt(4.5 / 6.5) = 1 - 3 / sqrt(13) = 0.16795.
  const WelchTest w = welch_t_test({1.0, 3.0}, {4.0, 6.0});
  EXPECT_NEAR(w.t, -3 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(w.degrees_of_freedom, 2.0, 1e-14);
  EXPECT_NEAR(w.p_value, 1 - 3 / std::sqrt(13.0), 1e-12);
  EXPECT_NEAR(w.p_value, p_two_dof(w.t), 1e-12);
  EXPECT_FALSE(w.significant);
  // One variance zero: {1, 1} against {-1, 1}: se^2 = 0 + 2 / 2 = 1, t = (1 - 0) / 1 = 1,
  // d.f. = n_b - 1 = 1 (Cauchy), p = 1 - (2 / pi) atan(1) = 0.5.
  const WelchTest c = welch_t_test({1.0, 1.0}, {-1.0, 1.0});
  EXPECT_NEAR(c.t, 1.0, 1e-15);
  EXPECT_NEAR(c.degrees_of_freedom, 1.0, 1e-14);
  EXPECT_NEAR(c.p_value, 0.5, 1e-12);
}

TEST(MassStatisticsWelch, NistDegreesOfFreedom) {
  // NIST/SEMATECH e-Handbook 1.3.5.3 (two-sample t-test, AUTO83B.DAT): sample 1 n = 249,
  // mean 20.14458, s = 6.41470; sample 2 n = 79, mean 30.48101, s = 6.10771; unequal-variance
  // degrees of freedom 136.8750. Samples with exactly those statistics: the mean once and
  // (n - 1) / 2 values at mean +- s each (squared deviations sum to (n - 1) s^2).
  auto sample = [](int n, double mean, double s) {
    std::vector<double> x = {mean};
    for (int i = 0; i < (n - 1) / 2; ++i) x.insert(x.end(), {mean - s, mean + s});
    return x;
  };
  const WelchTest w = welch_t_test(sample(249, 20.14458, 6.41470), sample(79, 30.48101, 6.10771));
  EXPECT_NEAR(w.degrees_of_freedom, 136.8750, 0.5e-4);
  // The handbook's printed T = -12.62059 is the pooled statistic; Welch's is
  // -10.33643 / sqrt(6.41470^2 / 249 + 6.10771^2 / 79) = -12.946 (by hand).
  EXPECT_NEAR(w.t, -10.33643 / std::sqrt(6.41470 * 6.41470 / 249 + 6.10771 * 6.10771 / 79), 1e-9);
  EXPECT_NEAR(w.t, -12.946, 0.5e-3);
  EXPECT_LT(w.p_value, 1e-20);
  EXPECT_TRUE(w.significant);
}

TEST(MassStatisticsWelch, ZeroVariances) {
  const WelchTest same = welch_t_test({2.0, 2.0, 2.0}, {2.0, 2.0});
  EXPECT_EQ(same.t, 0.0);
  EXPECT_EQ(same.p_value, 1.0);
  EXPECT_EQ(same.degrees_of_freedom, 3.0);  // pooled n_a + n_b - 2
  EXPECT_FALSE(same.significant);
  const WelchTest apart = welch_t_test({2.0, 2.0}, {3.0, 3.0});
  EXPECT_EQ(apart.t, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(apart.p_value, 0.0);
  EXPECT_EQ(apart.degrees_of_freedom, 2.0);
  EXPECT_TRUE(apart.significant);
}

TEST(MassStatisticsWelch, ErrorCases) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(welch_t_test({1.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(welch_t_test({1.0, 2.0}, {}), std::invalid_argument);
  EXPECT_THROW(welch_t_test({1.0, nan}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(welch_t_test({1.0, 2.0}, {1.0, 2.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(welch_t_test({1.0, 2.0}, {1.0, 2.0}, 1.0), std::invalid_argument);
}

TEST(MassStatisticsRecords, SummaryPerComponent) {
  // Masses 99, 101, 100, 100: mean 100, s^2 = (1 + 1) / 3. Component k of record i is
  // (k + 1) + i, so each component has mean (k + 1) + 1.5 and s^2 = (2.25 + 0.25) * 2 / 3 = 5/3.
  std::vector<MassProperties> sets;
  const std::array<double, 4> masses = {99, 101, 100, 100};
  for (int i = 0; i < 4; ++i) {
    std::array<double, 9> c{};
    for (int k = 0; k < 9; ++k) c[k] = k + 1 + i;
    sets.push_back(record(masses[i], c));
  }
  const MassSummary s = summarize(sets, 0.9);
  EXPECT_EQ(s.mass.count, 4);
  EXPECT_NEAR(s.mass.mean, 100.0, 1e-13);
  EXPECT_NEAR(*s.mass.std, std::sqrt(2.0 / 3.0), 1e-13);
  for (int k = 0; k < 9; ++k) {
    SCOPED_TRACE(mass_component_names()[k]);
    const SampleSummary& c = s.components[k];
    EXPECT_EQ(c.count, 4);
    EXPECT_NEAR(c.mean, k + 2.5, 1e-13);
    EXPECT_NEAR(*c.std, std::sqrt(5.0 / 3.0), 1e-13);
    // t(0.95, 3) = 2.353 from the published table (4 significant digits), se = s / 2.
    EXPECT_NEAR(half_width(c), 2.353 * std::sqrt(5.0 / 3.0) / 2, 0.5e-3 * std::sqrt(5.0 / 3.0) / 2);
  }
}

TEST(MassStatisticsRecords, CompareAlgorithmsFlagsTheShiftedComponent) {
  // Identical records except Jzz: 40.0, 40.1, 39.9, 40.0 against 41.0, 41.1, 40.9, 41.0.
  // Jzz: s^2 = 0.02 / 3 in both, se^2 = 2 (0.02 / 3) / 4 = 1/300, t = -1 / sqrt(1/300) = -sqrt(300),
  // d.f. = (2 v)^2 / (2 v^2 / 3) = 6. Every other component: both variances zero, equal means.
  const std::array<double, 9> base = {0.1, -0.2, 0.5, 10, 20, 40, 0.2, -0.1, 0.0};
  std::vector<MassProperties> a, b;
  for (double d : {0.0, 0.1, -0.1, 0.0}) {
    std::array<double, 9> ca = base, cb = base;
    ca[5] = 40 + d;
    cb[5] = 41 + d;
    a.push_back(record(100, ca));
    b.push_back(record(100, cb));
  }
  const std::array<WelchTest, 9> tests = compare_algorithms(a, b);
  for (int k = 0; k < 9; ++k) {
    SCOPED_TRACE(mass_component_names()[k]);
    if (k == 5) {
      EXPECT_NEAR(tests[k].t, -std::sqrt(300.0), 1e-9);
      EXPECT_NEAR(tests[k].degrees_of_freedom, 6.0, 1e-9);
      EXPECT_LT(tests[k].p_value, 1e-5);
      EXPECT_TRUE(tests[k].significant);
    } else {
      EXPECT_EQ(tests[k].t, 0.0);
      EXPECT_EQ(tests[k].p_value, 1.0);
      EXPECT_FALSE(tests[k].significant);
    }
  }
  EXPECT_THROW(compare_algorithms({a[0]}, b), std::invalid_argument);
}

TEST(MassStatisticsAccuracy, HandMadeSetsWithInclusiveLimits) {
  // Reference: CoG (0.1, -0.2, 0.5) m, Jxx 10, Jyy 20, Jzz 40, Jxy 0.2, Jxz -0.1, Jyz 0 kg m^2.
  // Limits: x, y +-0.003 m; z +-0.005 m; Jxx +-0.3, Jyy +-0.6, Jzz +-1.2; products +-0.015 * 40 = +-0.6.
  const std::array<double, 9> ref = {0.1, -0.2, 0.5, 10, 20, 40, 0.2, -0.1, 0.0};
  const MassProperties reference = record(100, ref);
  std::vector<MassProperties> sets;
  sets.push_back(reference);  // 0: all inside
  // 1: every component exactly at its limit: inside, the limits are inclusive. Jyy = 19.4 is 3 % of
  // the reference (20) below it, not 3 % of itself (0.582); the products use the reference's Jzz, not 41.2.
  sets.push_back(record(100, {0.103, -0.203, 0.495, 10.3, 19.4, 41.2, 0.8, -0.7, 0.6}));
  std::array<double, 9> c = ref;  // 2: xG and Jxx just outside
  c[0] = 0.1031;
  c[3] = 9.69;
  sets.push_back(record(100, c));
  c = ref;  // 3: zG and Jxy outside, Jyz at its lower limit
  c[2] = 0.506;
  c[6] = 0.81;
  c[8] = -0.6;
  sets.push_back(record(100, c));
  c = ref;  // 4: yG and Jzz outside
  c[1] = -0.1969;
  c[5] = 38.7;
  sets.push_back(record(100, c));

  const AccuracyShare share = share_within_accuracy(sets, reference);
  const std::array<double, 9> expected = {0.8, 0.8, 0.8, 0.8, 1.0, 0.8, 0.8, 1.0, 1.0};
  for (int k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(share.component[k], expected[k]) << mass_component_names()[k];
  EXPECT_DOUBLE_EQ(share.all, 0.4);  // sets 0 and 1

  // Tighter limits move set 1 out everywhere but leave the reference in.
  AccuracyLimits tight;
  tight.moment_relative = 0.02;
  tight.product_of_largest = 0.01;
  tight.cog_in_plane_m = 0.002;
  tight.cog_height_m = 0.004;
  EXPECT_DOUBLE_EQ(share_within_accuracy({reference, sets[1]}, reference, tight).all, 0.5);
}

TEST(MassStatisticsAccuracy, InclusiveSlackIsOnlyRounding) {
  const std::array<double, 9> ref = {0.1, -0.2, 0.5, 10, 20, 40, 0.2, -0.1, 0.0};
  std::array<double, 9> c = ref;
  c[0] = 0.1 + 0.003 * (1 + 1e-9);  // 3 pm beyond the limit: outside
  c[3] = 10 * (1 - 0.03 * (1 + 1e-9));
  const AccuracyShare share = share_within_accuracy({record(100, c)}, record(100, ref));
  EXPECT_EQ(share.component[0], 0.0);
  EXPECT_EQ(share.component[3], 0.0);
  EXPECT_EQ(share.component[1], 1.0);
  // A non-finite component is outside.
  c = ref;
  c[4] = std::numeric_limits<double>::infinity();
  c[6] = std::numeric_limits<double>::quiet_NaN();
  const AccuracyShare bad = share_within_accuracy({record(100, c)}, record(100, ref));
  EXPECT_EQ(bad.component[4], 0.0);
  EXPECT_EQ(bad.component[6], 0.0);
  EXPECT_EQ(bad.all, 0.0);
}

TEST(MassStatisticsAccuracy, ErrorCases) {
  const MassProperties reference = record(100, {0.1, -0.2, 0.5, 10, 20, 40, 0.2, -0.1, 0.0});
  EXPECT_THROW(share_within_accuracy({}, reference), std::invalid_argument);
  AccuracyLimits negative;
  negative.cog_height_m = -0.001;
  EXPECT_THROW(negative.validate(), std::invalid_argument);
  EXPECT_THROW(share_within_accuracy({reference}, reference, negative), std::invalid_argument);
  AccuracyLimits nan;
  nan.moment_relative = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(nan.validate(), std::invalid_argument);
  EXPECT_NO_THROW(AccuracyLimits{}.validate());
  MassProperties broken = reference;
  broken.inertia(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(share_within_accuracy({reference}, broken), std::invalid_argument);
}

TEST(MassStatisticsNormalProbability, BlomPositionsAndQuantiles) {
  // n = 5: p_i = (i - 3/8) / 5.25. Reference quantiles from Python's statistics.NormalDist().inv_cdf
  // (run once offline; scipy was not available): Phi^-1(0.880952) = 1.1797611176, Phi^-1(0.690476) = 0.4972005707.
  const std::vector<NormalProbabilityPoint> points = normal_probability({3, -1, 2, 0, 10});
  ASSERT_EQ(points.size(), 5u);
  const std::array<double, 5> sorted = {-1, 0, 2, 3, 10};
  const std::array<double, 5> z = {-1.1797611176, -0.4972005707, 0, 0.4972005707, 1.1797611176};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(points[i].value, sorted[i]);
    EXPECT_NEAR(points[i].probability, (i + 1 - 0.375) / 5.25, 1e-15);
    EXPECT_NEAR(points[i].quantile, z[i], 1e-9);  // the reference's 10 printed decimals
  }
  EXPECT_NEAR(points[2].quantile, 0.0, 1e-15);  // Phi^-1(0.5) = 0

  // Blom positions never hit 0.975 exactly; with n = 25, p_25 = 24.625 / 25.25 = 0.975248 lies next
  // to it, so the known Phi^-1(0.975) = 1.959964 plus one Taylor step dp / phi(1.959964) is the
  // reference (the neglected second-order term is 1.8e-5).
  std::vector<double> values(25);
  for (int i = 0; i < 25; ++i) values[i] = 25 - i;
  const std::vector<NormalProbabilityPoint> many = normal_probability(values);
  const double z975 = 1.959964;
  const double phi = std::exp(-z975 * z975 / 2) / std::sqrt(2 * std::numbers::pi);
  EXPECT_NEAR(many.back().quantile, z975 + (24.625 / 25.25 - 0.975) / phi, 5e-5);
  // Every quantile maps back to its position through the CDF written with std::erfc.
  for (std::size_t i = 0; i < many.size(); ++i) {
    EXPECT_EQ(many[i].value, static_cast<double>(i + 1));
    EXPECT_NEAR(0.5 * std::erfc(-many[i].quantile / std::numbers::sqrt2), many[i].probability, 1e-14);
    EXPECT_NEAR(many[i].quantile, -many[many.size() - 1 - i].quantile, 1e-13);  // symmetric
  }
}

TEST(MassStatisticsNormalProbability, EmptyAndErrorCases) {
  EXPECT_TRUE(normal_probability({}).empty());
  const std::vector<NormalProbabilityPoint> one = normal_probability({7.5});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_DOUBLE_EQ(one[0].probability, 0.5);
  EXPECT_NEAR(one[0].quantile, 0.0, 1e-15);
  EXPECT_THROW(normal_probability({1.0, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
  EXPECT_THROW(normal_probability({std::numeric_limits<double>::infinity()}), std::invalid_argument);
}

TEST(MassStatisticsNormalProbability, OrderStatisticBandClosedFormsAndCoverage) {
  // The smallest of n uniforms has CDF 1 - (1 - x)^n, the largest x^n, the middle one of three
  // 3x^2 - 2x^3: each band edge, mapped back through Phi (written with std::erfc), lies at the
  // two-sided 2-sigma tail t = Phi(-2) of its rank's distribution.
  const double t = 0.5 * std::erfc(2.0 / std::numbers::sqrt2);
  auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); };
  for (const std::size_t n : {1u, 2u, 5u, 12u}) {
    const std::vector<OrderStatisticBand> band = normal_order_statistic_band(n, 2.0);
    ASSERT_EQ(band.size(), n);
    const double k = static_cast<double>(n);
    EXPECT_NEAR(1 - std::pow(1 - Phi(band.front().lower), k), t, 1e-12) << n;
    EXPECT_NEAR(1 - std::pow(1 - Phi(band.front().upper), k), 1 - t, 1e-12) << n;
    EXPECT_NEAR(std::pow(Phi(band.back().lower), k), t, 1e-12) << n;
    EXPECT_NEAR(std::pow(Phi(band.back().upper), k), 1 - t, 1e-12) << n;
    for (std::size_t i = 0; i < n; ++i) {  // symmetric about the median rank
      EXPECT_NEAR(band[i].lower, -band[n - 1 - i].upper, 1e-10) << n << " " << i;
      EXPECT_LT(band[i].lower, band[i].upper);
    }
  }
  EXPECT_NEAR(normal_order_statistic_band(1, 2.0)[0].lower, -2.0, 1e-12);  // one value: +-2 sigma itself
  const OrderStatisticBand mid = normal_order_statistic_band(3, 2.0)[1];
  auto middle_of_three = [&](double z) { return 3 * std::pow(Phi(z), 2) - 2 * std::pow(Phi(z), 3); };
  EXPECT_NEAR(middle_of_three(mid.lower), t, 1e-12);
  EXPECT_NEAR(middle_of_three(mid.upper), 1 - t, 1e-12);

  // Coverage by simulation: of 20000 normal samples of 5, each ranked value falls inside its band
  // with probability 1 - 2t = 0.9545; three binomial standard deviations are 0.0044.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const std::vector<OrderStatisticBand> band = normal_order_statistic_band(5, 2.0);
  std::array<int, 5> inside{};
  const int draws = 20000;
  for (int d = 0; d < draws; ++d) {
    std::array<double, 5> x;
    for (double& v : x) v = normal(rng);
    std::sort(x.begin(), x.end());
    for (int i = 0; i < 5; ++i) inside[i] += x[i] > band[i].lower && x[i] < band[i].upper;
  }
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(inside[i] / double(draws), 1 - 2 * t, 0.0044) << "rank " << i + 1;
  EXPECT_THROW(normal_order_statistic_band(3, 0.0), std::invalid_argument);
  EXPECT_THROW(normal_order_statistic_band(3, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}
