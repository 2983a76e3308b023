// Model against measurement (diagnose/history_comparison.hpp, diagnose/swing_band.hpp): noise
// estimate, swing band, swing-state fit, record checks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "diagnose/history_comparison.hpp"
#include "identify/identification_kinematics.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

rig::RigModel noisy_trifilar() { return test::noisy_trifilar(); }

rig::Record pushed(const rig::RigSystem& sys, int history, std::uint64_t seed = 7) {
  const rig::Linearization lin = rig::linearize(sys);
  rig::HistoryRequest req;
  req.push = rig::draw_push(sys, seed, 0, history);
  req.duration_s = 15.0;
  req.noise_seed = rig::noise_seed(seed, 0, history);
  req.linearization = &lin;
  return rig::simulate_history(sys, lin.equilibrium.configuration, req);
}

// The noise is found within 5 % (7500 samples: the MAD's own scatter is ~1.5 %).
TEST(Compare, NoiseEstimateFindsTheSensorNoise) {
  const rig::RigSystem sys(noisy_trifilar());
  const Eigen::VectorXd sigma = diagnose::channel_noise(diagnose::channels_of(pushed(sys, 0)));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sigma(c), 1.0, 0.05) << c;
  for (int c = 3; c < 9; ++c) EXPECT_NEAR(sigma(c), 2e-5, 1e-6) << c;
}

// Pass band flat to 1e-3 up to 1.25 x the highest swing mode, 60 dB down from 3 x.
TEST(Compare, SwingBandPassesTheSwingAndStopsAbove) {
  const double h = 0.002, f_swing = 0.7;
  const diagnose::SwingBand b = diagnose::swing_band(h, f_swing);
  EXPECT_NEAR(b.kernel.sum(), 1.0, 1e-12);
  auto gain = [&](double f) {
    double g = 0;
    const int m = b.half_width();
    for (int k = -m; k <= m; ++k) g += b.kernel(k + m) * std::cos(2 * std::numbers::pi * f * k * h);
    return g;
  };
  for (double f : {0.1, 0.5, 0.7, 1.25 * f_swing}) EXPECT_NEAR(gain(f), 1.0, 1e-3) << f;
  for (double f : {3.0 * f_swing, 4.8, 20.0, 200.0}) EXPECT_LE(std::abs(gain(f)), 1e-3) << f;
  EXPECT_NEAR(b.noise_gain(), b.kernel.norm(), 1e-15);
}

// A dropped sample is bridged by interpolation: a linear signal stays exact.
TEST(Compare, UniformRecordBridgesADroppedSample) {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(101, 0.0, 1.0);
  Eigen::VectorXd t2(100);
  t2 << t.head(40), t.tail(60);
  Eigen::MatrixXd x(100, 1);
  x.col(0) = 3.0 * t2.array() + 1.0;
  const diagnose::UniformRecord u = diagnose::uniform_record(t2, x);
  ASSERT_EQ(u.t.size(), 101);
  EXPECT_NEAR(u.step_s, 0.01, 1e-15);
  for (Eigen::Index k = 0; k < 101; ++k) EXPECT_NEAR(u.channels(k, 0), 3.0 * u.t(k) + 1.0, 1e-12);
}

// Noise-free data predicted from a known swing state: the fit finds it back.
TEST(Compare, SwingStateFoundBackFromNoiseFreeData) {
  const diagnose::ResponseModel rm(noisy_trifilar());
  diagnose::SwingState truth;
  truth << 0.02, -0.01, 0.03, 0.05, 0.02, -0.04;
  rig::Record h;
  h.t = Eigen::VectorXd::LinSpaced(3001, 0.0, 6.0);
  const Eigen::MatrixXd y = diagnose::predict_channels(rm, truth, h.t);
  h.force = y.leftCols(3);
  h.alpha = y.middleCols(3, 3);
  h.beta = y.rightCols(3);
  const diagnose::HistoryComparison c = diagnose::compare_history(rm, h, "exact", {});
  EXPECT_TRUE(c.fit.converged);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(c.fit.state(k), truth(k), 1e-6 * (1 + std::abs(truth(k)))) << k;
  EXPECT_LE(c.nrmse.maxCoeff(), 1e-5);
}

// The rig file's `simulation.method` is honoured by compare's model response
// as by `rigflex simulate`: CVODE's BDF gives another prediction of the same
// swing. The encoder angles agree within both integrators' truncation error
// (generalized-alpha's period error at >= 30 steps per period is ~0.1 % per
// period; 6 s is ~4 swing periods); the forces differ by the rods' bounce,
// which BDF keeps and generalized-alpha damps (docs/rig.md), so only their
// means over the record are compared, to 0.1 % of the static rod force.
TEST(Compare, TheRigFilesIntegrationMethodIsHonoured) {
  rig::RigModel bdf = noisy_trifilar();
  bdf.simulation.method = rig::IntegrationMethod::bdf;
  const diagnose::ResponseModel ga_model(noisy_trifilar()), bdf_model(bdf);
  diagnose::SwingState s;
  s << 0.02, -0.01, 0.03, 0.05, 0.02, -0.04;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(3001, 0.0, 6.0);
  const Eigen::MatrixXd ga = diagnose::predict_channels(ga_model, s, t);
  const Eigen::MatrixXd cv = diagnose::predict_channels(bdf_model, s, t);
  ASSERT_EQ(cv.rows(), ga.rows());
  EXPECT_GT((cv - ga).cwiseAbs().maxCoeff(), 0.0) << "the same integrator ran twice";
  for (Eigen::Index j = 3; j < ga.cols(); ++j) {
    const double range = ga.col(j).maxCoeff() - ga.col(j).minCoeff();
    EXPECT_LT((cv.col(j) - ga.col(j)).cwiseAbs().maxCoeff(), 1e-3 * range) << "angle channel " << j;
  }
  for (Eigen::Index j = 0; j < 3; ++j) {
    const double mean = ga.col(j).mean();
    EXPECT_NEAR(cv.col(j).mean(), mean, 1e-3 * std::abs(mean)) << "force channel " << j;
  }
}

// A record of the model itself, with noise: the swing-band residual is at
// the noise (ratio 0.7-1.3 for ~2000 band terms over 3 s), and each
// channel's band NRMSE within 1.5x of what the filtered noise alone gives
// (sigma x noise gain / the channel's band std; the band samples are
// correlated, so the estimate scatters by ~10 %).
TEST(Compare, OwnNoisyRecordIsMatchedToTheNoise) {
  const diagnose::ResponseModel rm(noisy_trifilar());
  for (int j = 0; j < 2; ++j) {
    const diagnose::HistoryComparison c = diagnose::compare_history(rm, pushed(rm.system, j), "h", {});
    EXPECT_TRUE(c.fit.converged);
    EXPECT_GT(c.fit.whitened_rms, 0.7);
    EXPECT_LT(c.fit.whitened_rms, 1.3);
    for (int ch = 0; ch < 9; ++ch) {
      const Eigen::VectorXd y = c.target.measured.col(ch);
      const double sd = std::sqrt((y.array() - y.mean()).square().mean());
      const double floor = c.target.sigma(ch) * c.target.band.noise_gain() / sd;
      EXPECT_LT(c.nrmse(ch), 1.5 * floor) << ch;
    }
  }
}

TEST(Compare, RecordsThatCannotComeFromTheRigAreRefused) {
  const diagnose::ResponseModel rm(noisy_trifilar());
  rig::Record h = pushed(rm.system, 0);
  rig::Record up = h;
  up.beta(10, 1) = 2.0;  // rad: the rod above its joint
  try {
    diagnose::compare_history(rm, up, "up", {});
    FAIL() << "no error";
  } catch (const rig::RecordError& e) {
    EXPECT_EQ(e.sample(), 10);
    EXPECT_EQ(e.channel(), "beta2");
  }
  rig::Record deg = h;
  deg.alpha *= 180.0 / std::numbers::pi;  // degrees: the joints no longer form the frame
  deg.beta *= 180.0 / std::numbers::pi;
  EXPECT_THROW(diagnose::compare_history(rm, deg, "deg", {}), rig::RecordError);
  rig::Record two = h;
  two.force = h.force.leftCols(2);
  EXPECT_THROW(diagnose::compare_history(rm, two, "two", {}), std::invalid_argument);
}

}  // namespace
