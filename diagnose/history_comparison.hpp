#pragma once
// Model against measurement, history by history. The record is put on a
// uniform time grid; each channel's noise is estimated from the record; the
// swing state is fitted to the record's first seconds by Levenberg-Marquardt
// on the swing-band residuals (diagnose/swing_band.hpp), each channel weighted by
// its filtered noise; the whole record is simulated from it.
//
// Normalized RMS error of a channel: RMS(measured - model) / std(measured),
// the residual against what the channel's signal varies by (the static load
// of a rod would make a force residual look small otherwise), in the swing
// band (both signals through the band's low-pass, diagnose/swing_band.hpp): the
// swing and the quasi-static response, where the identification works and
// the catalogue's effects act, without the noise and the frames' ringing
// after release. The raw figure (every sample, noise and ringing included)
// is kept beside it. Overall: the RMS over channels of the channels' values;
// the force figure over the load cells only.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "diagnose/model_response.hpp"
#include "diagnose/swing_band.hpp"

namespace rigflex::diagnose {

struct CompareOptions {
  double fit_window_s = 3.0;  // the swing state is fitted over the record's first seconds
  int max_iterations = 12;    // Levenberg-Marquardt
  void validate() const;      // std::invalid_argument naming the field
};

// Noise standard deviation of each channel, from the record itself: the
// median absolute third difference (a swing, even a 50 Hz frame vibration
// sampled at 500 Hz, hardly shows in third differences; white noise gives
// variance 20 sigma^2), so outliers and the signal do not inflate it. Floored
// at 1e-9 of the channel's scale for noise-free records.
Eigen::VectorXd channel_noise(const Eigen::MatrixXd& channels);

// What the fits compare a model with: one record in the swing band.
struct BandTarget {
  UniformRecord record;
  Eigen::VectorXd sigma;          // raw noise per channel
  SwingBand band;
  std::vector<Eigen::Index> at;   // band samples of the whole record
  Eigen::MatrixXd measured;       // filtered at `at`
  Eigen::VectorXd weight;         // 1 / filtered noise, per channel
  // Band samples up to t(0) + seconds.
  Eigen::Index rows_within(double seconds) const;
};
BandTarget band_target(const ResponseModel& m, const rig::Record& record);

// Noise-weighted swing-band residual (measured - model) over the first
// `rows` band samples (all when rows < 0), stacked channel by channel.
Eigen::VectorXd band_residual(const ResponseModel& m, const SwingState& s, const BandTarget& target,
                              Eigen::Index rows = -1);

struct SwingFit {
  SwingState state = SwingState::Zero();
  int iterations = 0;
  bool converged = false;
  double whitened_rms = 0;  // RMS of the noise-weighted band residual over the fit window (1 = at the noise)
};

// Levenberg-Marquardt from `guess` over the band samples within the fit window.
SwingFit fit_swing_state(const ResponseModel& m, const BandTarget& target, const SwingState& guess,
                         const CompareOptions& options);

// The frames' ringing at the record's start: the elastic state fitted by
// linear least squares to the raw (not band-limited) noise-weighted
// residual over the fit window, the swing state held. Kept only if the
// residual falls.
ElasticState fit_elastic_state(const ResponseModel& m, const BandTarget& target, const SwingState& s,
                               double window_s);

struct HistoryComparison {
  std::string source;          // file or label
  BandTarget target;
  SwingFit fit;
  ElasticState elastic;
  Eigen::MatrixXd model;       // on target.record.t, channels_of layout
  Eigen::MatrixXd band_model;  // the model in the swing band, at target.at
  Eigen::VectorXd nrmse;       // per channel, swing band
  Eigen::VectorXd raw_nrmse;   // per channel, every sample
  double fit_window_nrmse = 0; // overall, swing band, over the fit window only
  const Eigen::VectorXd& t() const { return target.record.t; }
  const Eigen::MatrixXd& measured() const { return target.record.channels; }
  Eigen::MatrixXd residual() const { return target.record.channels - model; }
};

// rig::RecordError (rig/record.hpp) when the record cannot
// come from this rig: an encoder angle that turns a rod above its joint, or
// lower joints (from the encoders) that do not form the carrying frame's
// joint pattern within max(20 mm, 5 % of its radius).
void check_record_fits_rig(const ResponseModel& m, const Eigen::VectorXd& t, const Eigen::MatrixXd& channels);

// One history: swing-state guess from the encoders, fit, simulation of the record.
HistoryComparison compare_history(const ResponseModel& m, const rig::Record& record, const std::string& source,
                                  const CompareOptions& options);

Eigen::VectorXd nrmse_of(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& model);
// RMS over channels of per-channel values; `first`, `count` select channels.
double rms_of(const Eigen::VectorXd& per_channel, Eigen::Index first, Eigen::Index count);
// Per-channel NRMSE over several histories (residuals and signal variances
// pooled), in the swing band or (raw) over every sample.
Eigen::VectorXd pooled_nrmse(const std::vector<HistoryComparison>& h, bool raw = false);

}  // namespace rigflex::diagnose
