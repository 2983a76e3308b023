#pragma once
// Where a model fails against measurements (compare's diagnostics): residual
// spectra with the model's modes beside them, amplitude decay of model and
// measurement, static offsets, the channels and time windows where the
// residual concentrates and how it trends along the record, whiteness, and
// the residual's correlation with the states (angle, velocity, sign of
// velocity, acceleration, rod force) - the signatures by which an engineer
// tells friction (sign of velocity) from drag (decay growing with
// amplitude), an offset from a wrong stiffness (a peak beside a mode).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "diagnose/history_comparison.hpp"

namespace rigflex::diagnose {

struct SpectrumPeak {
  std::string group;            // "force" or "angle"
  double frequency_hz = 0;
  double amplitude = 0;         // amplitude spectral density (unit / sqrt(Hz))
  double nearest_mode_hz = 0;   // the model's nearest mode (0: none)
};

struct ResidualSpectra {
  Eigen::VectorXd frequency_hz;
  // Welch estimates (Hann, 50 % overlap) averaged over the group's channels and the histories.
  Eigen::VectorXd residual_force, residual_angle, measured_force, measured_angle;
  std::vector<SpectrumPeak> peaks;  // largest local maxima of the residual, per group
};

struct DecayComparison {
  int history = 0;
  // Exponential decay rate (1/s) of the swing amplitude envelope: RMS over
  // windows of two longest swing periods of the angle channels, ln fitted
  // linearly in time. > 0 decays.
  double measured_rate = 0, model_rate = 0;
};

struct ResidualWindow {
  int history = 0;
  double t_start = 0, t_end = 0;
  double share = 0;  // of the total noise-weighted residual energy
};

struct StateCorrelation {
  std::string state;    // angle, velocity, sign_of_velocity, acceleration, rod_force
  double largest = 0;   // largest |Pearson correlation| over the channels
  std::string channel;  // where
  Eigen::VectorXd per_channel;
};

struct ResidualAnalysis {
  std::vector<std::string> channels;
  Eigen::VectorXd noise;              // sigma per channel, mean over histories
  Eigen::VectorXd noise_ratio;        // residual RMS / noise per channel (1: at the noise)
  Eigen::VectorXd static_offset;      // mean residual per channel
  Eigen::VectorXd offset_in_noise;    // static offset / its standard error from the noise
  Eigen::VectorXd lag1;               // lag-one autocorrelation of the residual (0: white)
  Eigen::VectorXd channel_share;      // share of the noise-weighted residual energy per channel
  std::vector<double> trend_t;        // window centres (s from the record's start)
  std::vector<double> trend_nrmse;    // overall NRMSE per window, pooled over histories
  double trend_slope = 0;             // d(overall NRMSE)/dt, least squares (1/s)
  std::vector<ResidualWindow> windows;  // largest first
  std::vector<DecayComparison> decay;
  double extra_decay_rate = 0;        // mean measured - model rate (1/s)
  ResidualSpectra spectra;
  std::vector<double> mode_frequencies_hz;
  std::vector<std::string> mode_kinds;
  std::vector<StateCorrelation> correlations;
};

ResidualAnalysis analyse_residuals(const ResponseModel& m, const std::vector<HistoryComparison>& histories);

}  // namespace rigflex::diagnose
