#pragma once
// Can the records tell two fitted models apart? Two catalogue effects are
// not nested (a fixed frame's compliance is no special case of a carrying
// frame's), so an F test cannot compare them. Vuong's test for non-nested
// models can: the log-likelihood ratio of the two fits against its
// standard error. The noise-weighted band residuals r have unit variance at
// the noise, so the ratio is sum (r_2^2 - r_1^2) / 2 = sum d m with
// d = r_2 - r_1 (the two models' predictions apart: the noise cancels) and
// m = (r_1 + r_2) / 2. If both models are equally far from the truth, the
// sum's mean is zero and its variance that of the noise in m along d:
// s^2 sum d^2 / independence - the band samples' correlation as the
// diagnosis counts it, s^2 the better fit's residual per sample (at least
// the noise's 1: a common model error both fits leave counts as noise).
// The ratio over its standard error is normal. Schwarz's penalty, (p_1 -
// p_2) / 2 ln(n) with n the independent samples, is reported beside it but
// does not enter the test: two nearly equal fits have a vanishing standard
// error, and a fixed penalty over it would call any two look-alikes apart
// in favour of the leaner. Whether the records tell them apart is the
// data's question; which of two equals goes first is the ranking's
// (diagnose/diagnosis.hpp: the leaner one).
//
// Why not Vuong's own variance (the spread of the per-sample ratios, or of
// block sums): a fit far from the data has a misfit that varies with the
// swing, and that deterministic variation counts as spread: on 3 records
// of 8 s a fit at the noise against one that explains 88 % (not 99.9 %) of
// the residual came out p = 0.17 with block sums; Newey-West's long-run
// variance still gave p = 0.03 for a misfit of 10 x the noise decaying
// over the first rows (tests/diagnose/test_fit_discrimination.cpp).
//
// Reference: Q. H. Vuong, Likelihood ratio tests for model selection and
// non-nested hypotheses, Econometrica 57 (1989) 307-333.
#include <Eigen/Core>
#include <vector>

namespace rigflex::diagnose {

struct FitDiscrimination {
  double log_likelihood_ratio = 0;  // first over second: > 0 favours the first
  double penalized = 0;             // less Schwarz's penalty
  double z = 0;                     // the (unpenalized) ratio over its standard error
  double p_value = 1;               // two-sided, of a ratio this far from 0 if both fit equally well
};

struct DiscriminationInput {
  // Per history: the residual stacked channel by channel, `rows[j]` band
  // samples per channel.
  const std::vector<Eigen::VectorXd>* first = nullptr;
  const std::vector<Eigen::VectorXd>* second = nullptr;
  std::vector<Eigen::Index> rows;
  double independence = 1;          // independent share of the band samples (SwingBand::independence)
  double parameter_difference = 0;  // fitted parameters of the first minus the second's (for the penalty)
};

// std::invalid_argument when the residuals' shapes disagree with `rows`.
FitDiscrimination discriminate(const DiscriminationInput& in);

}  // namespace rigflex::diagnose
