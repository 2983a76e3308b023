#pragma once
// What another simulator's numerics leave between a model and its records.
//
// Records produced by a different simulator carry that simulator's
// integration error, mostly a small error of the swing's period (CVODE's
// BDF at its default relative tolerance 1e-6: about 1e-5), which grows
// over a record into a phase drift that the fits read as a change of the
// pendulum's length. Its size in noise units is not a constant: it grows
// with the sample rate (the band's noise density falls: at 1000 Hz half of
// 500 Hz's) and with a quieter logger, while a missing effect's does too.
// So diagnose's gate ("the model reaches the noise and the simulator's
// numerics") is set in both units: the larger of noise_excess x the noise
// and what a period error of DiagnosisOptions::period_tolerance leaves in
// these very records.
#include <vector>

#include "diagnose/history_comparison.hpp"

namespace rigflex::diagnose {

// The noise-weighted sum of squares over the band samples of `targets`
// that a relative period error `period_error` of every swing would leave
// once each record's phase is refitted: per record, eps (t - t0) dy/dt of
// the measured band signals (BandTarget::measured and the record beside
// it), minus its projection on dy/dt (the constant phase shift the swing
// states absorb), weighted as the fits weigh the residual.
// period_error >= 0; 0 gives 0.
double period_error_residual(const std::vector<const BandTarget*>& targets, double period_error);

}  // namespace rigflex::diagnose
