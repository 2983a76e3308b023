// bench_noise_estimate [--seeds N] [--rig trifilar|quadrifilar]:
// how well compare and diagnose measure the noise the swing band holds,
// with the sensors' noise white and coloured. Per noise kind - white, or
// the rig file's noise RMS through a first-order low-pass at 100, 30 or
// 8 Hz (an amplifier's bandwidth; records at 500 Hz) - and per seed: the
// nominal rig's six records of 15 s (tests/support/diagnosis_cases.hpp,
// measure_histories), and for each channel three estimates against the
// noise the band truly holds (white noise of the same spectral density in
// the swing band: the RMS x sqrt((1 + a) / (1 - a)) for the low-pass's
// AR(1) coefficient a):
//   third diff.  the median absolute third difference (channel_noise)
//   near band    the median over the bins from 3.5 to 15 x the highest
//                swing mode of a Welch spectrum (near_band_noise)
//   used         what the fits weigh by (band_noise: the first, or the
//                second / 1.3 where that is larger)
// each as min / median / max of estimate / truth over every channel and
// record, forces and angles apart; "near band taken" is the share of
// channels where the near-band estimate set the weight. A second table runs
// every acceptance case of tests/support/diagnosis_cases.hpp (the effect
// hidden, white noise): where an effect's own response (a frame's ringing
// after release, a harmonic) lay in the near band, the near-band estimate
// would rise with it; the table gives its largest ratio to the third
// differences' and the channels where it set the weight. Deterministic.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "diagnose/band_noise.hpp"
#include "diagnose/history_comparison.hpp"
#include "support/diagnosis_cases.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

struct Spread {
  std::vector<double> v;
  std::string text() const {
    std::vector<double> s = v;
    std::sort(s.begin(), s.end());
    char t[64];
    std::snprintf(t, sizeof t, "%.2f / %.2f / %.2f", s.front(), s[s.size() / 2], s.back());
    return t;
  }
};

struct Kind {
  Spread white, near, used;
  int taken = 0, channels = 0;
};

}  // namespace

int main(int argc, char** argv) {
  int seeds = 3;
  bool quadrifilar = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--seeds") {
        seeds = std::stoi(bench::option_value(argc, argv, i));
        if (seeds < 1) throw std::invalid_argument("--seeds must be >= 1");
      } else if (a == "--rig") {
        const std::string r = bench::option_value(argc, argv, i);
        if (r != "trifilar" && r != "quadrifilar") throw std::invalid_argument("--rig: trifilar or quadrifilar");
        quadrifilar = r == "quadrifilar";
      } else {
        throw std::invalid_argument("unknown option " + a);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_noise_estimate: %s\n", e.what());
    return 2;
  }
  const rig::RigModel truth = quadrifilar ? test::noisy_quadrifilar() : test::noisy_trifilar();
  const diagnose::ResponseModel m(truth);
  std::printf(
      "%s, seeds 1..%d, 6 records x 15 s at 500 Hz each; estimate / the band's true noise, "
      "min / median / max over channels and records\n\n",
      quadrifilar ? "quadrifilar 250 kg" : "trifilar 200 kg", seeds);
  std::printf("| noise | channels | third diff. | near band | used | near band taken |\n|---|---|---|---|---|---|\n");
  for (double corner : {0.0, 100.0, 30.0, 8.0}) {
    Kind forces, angles;
    for (int seed = 1; seed <= seeds; ++seed) {
      for (const rig::Record& r :
           test::measure_histories(truth, 1000 * static_cast<std::uint64_t>(seed) + 29, corner)) {
        const diagnose::BandTarget b = diagnose::band_target(m, r);
        const Eigen::VectorXd white = diagnose::channel_noise(b.record.channels);
        const Eigen::VectorXd near = diagnose::near_band_noise(b.record.channels, b.band);
        const double a = corner > 0 ? std::exp(-2.0 * 3.141592653589793 * corner / r.sample_rate_hz) : 0.0;
        const double colour = std::sqrt((1.0 + a) / (1.0 - a));
        for (Eigen::Index c = 0; c < white.size(); ++c) {
          const bool force = c < r.rods();
          Kind& k = force ? forces : angles;
          const double truth_sigma = colour * (force ? truth.sensors.force_noise_n : truth.sensors.angle_noise_rad);
          k.white.v.push_back(white(c) / truth_sigma);
          k.near.v.push_back(near(c) / truth_sigma);
          k.used.v.push_back(b.sigma(c) / truth_sigma);
          k.taken += b.sigma(c) > white(c);
          ++k.channels;
        }
      }
    }
    char label[32] = "white";
    if (corner > 0) std::snprintf(label, sizeof label, "low-pass %g Hz", corner);
    for (const auto& [name, k] : {std::pair<const char*, const Kind&>{"forces", forces}, {"angles", angles}}) {
      std::printf("| %s | %s | %s | %s | %s | %d of %d |\n", label, name, k.white.text().c_str(), k.near.text().c_str(),
                  k.used.text().c_str(), k.taken, k.channels);
    }
    std::fflush(stdout);
  }
  std::printf(
      "\nWhite noise, each acceptance case's truth (the effect hidden): near band / third diff.\n\n"
      "| case | max | near band taken |\n|---|---|---|\n");
  std::vector<std::string> cases = {"none", "below_noise"};
  for (int k = 0; k < test::kHiddenEffects; ++k) {
    if (const auto e = test::hidden_effect(k, truth)) cases.push_back(e->name());
  }
  cases.push_back("two_effects");
  for (const auto& name : cases) {
    const rig::RigModel hidden = test::case_truth(name, truth);
    const diagnose::ResponseModel mh(hidden);
    double worst = 0;
    int taken = 0, channels = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      for (const rig::Record& r : test::measure_histories(hidden, 1000 * static_cast<std::uint64_t>(seed) + 17)) {
        const diagnose::BandTarget b = diagnose::band_target(mh, r);
        const Eigen::VectorXd white = diagnose::channel_noise(b.record.channels);
        const Eigen::VectorXd near = diagnose::near_band_noise(b.record.channels, b.band);
        worst = std::max(worst, (near.array() / white.array()).maxCoeff());
        taken += static_cast<int>((b.sigma.array() > white.array()).count());
        channels += static_cast<int>(white.size());
      }
    }
    std::printf("| %s | %.2f | %d of %d |\n", name.c_str(), worst, taken, channels);
    std::fflush(stdout);
  }
  return 0;
}
