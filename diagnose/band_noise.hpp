#pragma once
// The noise a record's swing band holds, per channel.
//
// channel_noise (diagnose/history_comparison.hpp) measures the noise from
// third differences: near the Nyquist frequency. That is the swing band's
// noise only where the noise is white. A load cell amplifier or an
// anti-aliasing filter with its corner well below the Nyquist frequency
// colours it: its third differences then see a fraction of it (a
// first-order low-pass on records at 500 Hz: at 30 Hz a fifth, at 8 Hz a
// twentieth; bench/bench_noise_estimate), and a model as good as the
// sensors would stand tens to hundreds of times "above the noise" in the
// band - no fit could reach it, no body would be credible.
// So the noise is also measured just above the swing band, where the
// records hold little but noise: the median over the bins of a Welch
// spectrum from 3.5 to 15 x the highest swing mode (the swing itself
// subtracted first by the band's own low-pass, so that its line does not
// leak there; a frame's ringing line or a harmonic takes a few bins, which
// the median passes over), stated as the white noise of the same spectral
// density.
#include <Eigen/Core>

#include "diagnose/swing_band.hpp"

namespace rigflex::diagnose {

// Per channel of a uniform record: the standard deviation of white noise
// whose spectral density equals the channel's just above the swing band
// (see above); 0 for every channel where the record is too short for the
// estimate (fewer than 16 periodogram bins there).
Eigen::VectorXd near_band_noise(const Eigen::MatrixXd& channels, const SwingBand& band);

// The noise the fits weigh a channel by: the third differences' estimate,
// or the near-band one where it exceeds that by more than its own scatter
// can (kColouredNoiseMargin), divided by that margin - so white noise keeps
// its third-difference estimate, and coloured noise is weighed by at least
// its near-band level / margin.
Eigen::VectorXd band_noise(const Eigen::VectorXd& white, const Eigen::VectorXd& near_band);
inline constexpr double kColouredNoiseMargin = 1.3;

}  // namespace rigflex::diagnose
