#pragma once
// The swing band of a record: both the measured and the modelled signals go
// through the same zero-phase low-pass (a Blackman-windowed sinc) and are
// compared at a reduced rate. What the fits see is then the swing and the
// quasi-static response of the rig (everything the catalogue's effects
// change), not the decaying rod and frame vibrations that a release leaves
// and a six-number swing state cannot describe (a pushed record of a rigid
// trifilar shows 3 N of 300 Hz rod bounce in its first second against 1 N
// of noise; examples/large-rig rings at 4.8 Hz for the whole record), nor
// the white noise above the band.
#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace rigflex::diagnose {

struct SwingBand {
  double swing_hz = 0;     // the highest swing mode it was made for
  double cutoff_hz = 0;    // -6 dB point of the low-pass
  double step_s = 0;       // sample interval of the uniform record
  Eigen::VectorXd kernel;  // odd length, unit DC gain, symmetric
  int decimation = 1;      // every decimation-th filtered sample is compared
  int half_width() const { return static_cast<int>(kernel.size() / 2); }
  // Standard deviation of the filtered value for unit white noise.
  double noise_gain() const { return kernel.norm(); }
  // Filtered samples per independent one: decimated samples are nearly
  // uncorrelated when spaced 1 / (2 cutoff) apart.
  double independence() const { return std::min(1.0, 2.0 * cutoff_hz * decimation * step_s); }
};

// Pass band to 1.25 x the highest swing mode, stop band from 3 x (60 dB,
// Kaiser window; a rig that meets the design rule has its first deformation
// mode there, and a lightly damped frame mode that a release excites would
// otherwise dominate the force residual of even the true model); compared
// at four samples per cutoff period. The kernel spans 3.6 / (1.75 f_swing)
// seconds: records lose half of it at each end.
SwingBand swing_band(double step_s, double highest_swing_hz);

// Indices of the uniform samples where the filter has its whole kernel,
// every decimation-th, from `first` (or later) to `last` (or earlier).
std::vector<Eigen::Index> band_samples(const SwingBand& b, Eigen::Index samples, Eigen::Index first = 0,
                                       Eigen::Index last = -1);

// Filtered channels at the given sample indices: rows = indices.
Eigen::MatrixXd band_filter(const SwingBand& b, const Eigen::MatrixXd& channels, const std::vector<Eigen::Index>& at);

// A record on a uniform grid t0 + k h (h the median interval) by linear
// interpolation: a dropped sample or jittered time stamps do not shift the
// filters' time base.
struct UniformRecord {
  Eigen::VectorXd t;
  Eigen::MatrixXd channels;
  double step_s = 0;
};
UniformRecord uniform_record(const Eigen::VectorXd& t, const Eigen::MatrixXd& channels);

}  // namespace rigflex::diagnose
