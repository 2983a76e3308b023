#pragma once
// Welch's averaged periodogram, as the residual spectra and the near-band
// noise estimate both take it: half-overlapping Hann segments, each
// segment's mean removed (an offset would leak into the lowest bins).
#include <Eigen/Core>

namespace rigflex::diagnose {

struct WelchSums {
  Eigen::VectorXd power;    // per bin 0 .. n/2: the sum over segments of |FFT|^2
  int segments = 0;         // 0 where x is shorter than one segment (power all 0)
  double window_power = 0;  // sum of the squared window: a segment of unit white noise gives that per bin
};

// Segments of n >= 2 samples of x.
WelchSums welch_sums(const Eigen::VectorXd& x, int n);

}  // namespace rigflex::diagnose
