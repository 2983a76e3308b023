#pragma once
// Statistics of repeated mass-properties identifications: per-component
// summaries, Welch tests between two algorithms, the share of sets inside the
// rig's accuracy, and normal-probability plot data.
#include <array>
#include <optional>
#include <vector>

#include "fe/mass_properties.hpp"

namespace rigflex::identify {

// The nine identified components, in the order xG, yG, zG, Jxx, Jyy, Jzz,
// Jxy, Jxz, Jyz (products as stored: negative integrals).
std::array<double, 9> mass_components(const fe::MassProperties& p);
const std::array<const char*, 9>& mass_component_names();

struct SampleSummary {
  int count = 0;
  double mean = 0;
  std::optional<double> std;  // sample standard deviation (n - 1); none for count < 2
  // Two-sided Student-t interval of the mean; none for count < 2.
  std::optional<std::array<double, 2>> confidence_interval;
};
// Throws std::invalid_argument on an empty sample, confidence outside (0, 1)
// or non-finite values.
SampleSummary summarize(const std::vector<double>& x, double confidence = 0.95);

struct WelchTest {
  double t = 0, degrees_of_freedom = 0, p_value = 1;  // two-sided
  bool significant = false;                          // p_value < alpha
};
// t = (mean(a) - mean(b)) / sqrt(s_a^2 / n_a + s_b^2 / n_b), Welch-Satterthwaite
// degrees of freedom. Both variances zero: t = 0 and p = 1 for equal means,
// t = +-inf and p = 0 otherwise, with the pooled n_a + n_b - 2 degrees of
// freedom. Throws std::invalid_argument when a sample has fewer than 2 values,
// holds a non-finite value, or alpha is outside (0, 1).
WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b, double alpha = 0.05);

// Per-component summaries of repeated identifications (one record per
// measurement set).
struct MassSummary {
  SampleSummary mass;
  std::array<SampleSummary, 9> components;
};
MassSummary summarize(const std::vector<fe::MassProperties>& sets, double confidence = 0.95);

// Welch per component, e.g. rigid against flexible identification of the same
// sets. The samples are treated as independent (the pairing is not used).
std::array<WelchTest, 9> compare_algorithms(const std::vector<fe::MassProperties>& a,
                                            const std::vector<fe::MassProperties>& b, double alpha = 0.05);

// The rig's 2-sigma accuracy relative to a reference: each diagonal moment
// within moment_relative of its reference value, each product within
// product_of_largest of the reference's largest diagonal moment, the CoG
// within cog_in_plane_m along x and along y and within cog_height_m along z.
struct AccuracyLimits {
  double moment_relative = 0.03;
  double product_of_largest = 0.015;
  double cog_in_plane_m = 0.003;
  double cog_height_m = 0.005;
  void validate() const;  // std::invalid_argument unless every limit is finite and >= 0
};
struct AccuracyShare {
  std::array<double, 9> component{};  // share (0..1) of the sets inside the limit, per component
  double all = 0;                     // share of sets with every component inside
};
// Limits are inclusive: a deviation exactly at the limit is inside. A
// non-finite component is outside. Throws std::invalid_argument for no sets,
// a non-finite reference or invalid limits.
AccuracyShare share_within_accuracy(const std::vector<fe::MassProperties>& sets, const fe::MassProperties& reference,
                                    const AccuracyLimits& limits = {});

// Normal-probability plot data: the values sorted ascending, with Blom
// plotting positions p_i = (i - 3/8) / (n + 1/4), i = 1..n, and the
// standard-normal quantiles z_i = Phi^-1(p_i). Throws std::invalid_argument on
// non-finite values; no values give no points.
struct NormalProbabilityPoint {
  double value = 0, probability = 0, quantile = 0;
};
std::vector<NormalProbabilityPoint> normal_probability(std::vector<double> values);

// Where the i-th smallest of n normal values lies with the probability of
// +-`sigmas` standard deviations of a normal variable (2: 95.45 %), in
// standard-normal quantiles: the i-th order statistic of n uniforms is
// Beta(i, n + 1 - i), so its central interval maps through Phi^-1. On a
// normal probability plot the band around the line m + s z holds each point
// of a normal sample with that probability; a point outside it is an
// outlier or the sample is not normal. Throws std::invalid_argument for
// sigmas <= 0.
struct OrderStatisticBand {
  double lower = 0, upper = 0;  // standard-normal quantiles
};
std::vector<OrderStatisticBand> normal_order_statistic_band(std::size_t n, double sigmas);

}  // namespace rigflex::identify
