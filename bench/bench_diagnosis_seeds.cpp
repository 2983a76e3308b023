// bench_diagnosis_seeds [--seeds N] [--first S] [--cases a,b,...] [--threads N]
//                       [--relinearizations N] [--refinements N] [--relinearize-gain G]
//                       [--contender-gain G] [--contender-settled R] [--restart-span S]
//                       [--effects a,b,...] [--test-seed] [--rig trifilar|quadrifilar]
//                       [--noise-corner-hz F] [--sample-rate-hz F] [--truth-bdf-rtol R] [--histories N]
//                       [--verbose] [--progress]:
// issue 17's acceptance over many seeds, the study tests/acceptance runs one
// seed of. Per case - each catalogue effect hidden in the trifilar of
// tests/support/diagnosis_cases.hpp, two controls (nothing hidden; air drag
// a few hundred times weaker than the hidden case's, below the noise) and two effects at
// once (a rod length error and load-cell gains) - and per seed: the records
// simulated (6 histories of 15 s unless --histories, spec sensor noise), the user's model (CoG
// within +-3/+-3/+-7 mm, inertia from the rigid identification, rods
// nominal), diagnose with the whole catalogue, then what it found added:
// the chain's effects as its last step refitted them (the first-ranked
// effect's where none is significant) and the body's fitted offsets. One row per case:
//   named    seeds whose missing effect is the hidden one and nothing else
//            (controls: none named; two effects: both, one after the
//            other, in the chain)
//   fall     worst force (angle, where the effect shows more there) NRMSE
//            before / after adding what diagnose found (target >= 5)
//   zG fit   worst |fitted CoG height - truth|, mm (target <= 2)
//   zG id    worst |flexible identification's CoG height - truth| with the
//            effect added, mm (target <= 2)
//   s        mean diagnose wall time
// --relinearizations, --refinements, --relinearize-gain and --contender-gain set diagnose's
// fit budget (defaults: DiagnosisOptions'), for studies of what more
// iterations buy (--contender-settled: the residual / noise at which a
// contender is left as it is; 0 takes every one on; --restart-span: which
// contenders are restarted from their parameters zeroed one at a time, 0
// none); --effects tests only those candidates. --rig quadrifilar runs the
// cases on the four-rod rig of tests/support/rig_cases.hpp (rods of
// 2e7 N/m; its effects' sizes in tests/support/diagnosis_cases.hpp; no rod
// compliance case: the rods' stiffness is part of that model). --test-seed
// runs each case once with the seed tests/acceptance/test_uncertain_body.cpp
// gives it, to study the CI's case. --noise-corner-hz F passes the
// sensors' noise (its RMS as the rig states it) through a first-order
// low-pass at F Hz, as an amplifier's bandwidth colours it
// (tests/support/diagnosis_cases.hpp, add_coloured_noise); --sample-rate-hz
// records at that rate instead of the rig's 500 Hz (the data contract's
// range is 100-1000 Hz; the noise per sample as stated); --truth-bdf-rtol R
// simulates every case's records by CVODE's BDF at relative tolerance R
// (the clean control's integrator, otherwise only there), as records from
// another, accurate simulator would be; --histories N records per set
// instead of 6 (the independent data has 12). --verbose prints each run's ranking
// (explained share, significance, F-test p, residual / noise, notes) and chain
// on stderr; --progress prints diagnose's progress lines there, each with
// the seconds since the run began (where a run's time goes).
// Deterministic for the given seeds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/model_comparison.hpp"
#include "support/diagnosis_cases.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

struct Options {
  int seeds = 5, threads = 0;
  rigflex::diagnose::DiagnosisOptions diagnosis;
  std::uint64_t first = 1;
  bool test_seed = false, verbose = false, progress = false, quadrifilar = false;
  double noise_corner_hz = 0;  // > 0: the sensors' noise coloured by a first-order low-pass there
  double sample_rate_hz = 0;   // > 0: the sensors' rate, for the rig's
  double truth_rtol = 0;       // > 0: every case's records by BDF at this relative tolerance
  int histories = 6;           // records per set
  std::vector<std::string> cases;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seeds") {
      o.seeds = std::stoi(bench::option_value(argc, argv, i));
    } else if (a == "--first") {
      o.first = std::stoull(bench::option_value(argc, argv, i));
    } else if (a == "--cases") {
      o.cases = bench::split(bench::option_value(argc, argv, i));
    } else if (a == "--rig") {
      const std::string rig = bench::option_value(argc, argv, i);
      if (rig != "trifilar" && rig != "quadrifilar") throw std::invalid_argument("--rig: trifilar or quadrifilar");
      o.quadrifilar = rig == "quadrifilar";
    } else if (a == "--noise-corner-hz") {
      o.noise_corner_hz = std::stod(bench::option_value(argc, argv, i));
      if (!(o.noise_corner_hz > 0)) throw std::invalid_argument("--noise-corner-hz must be > 0");
    } else if (a == "--sample-rate-hz") {
      o.sample_rate_hz = std::stod(bench::option_value(argc, argv, i));
      if (!(o.sample_rate_hz > 0)) throw std::invalid_argument("--sample-rate-hz must be > 0");
    } else if (a == "--histories") {
      o.histories = std::stoi(bench::option_value(argc, argv, i));
      if (o.histories < 1) throw std::invalid_argument("--histories must be >= 1");
    } else if (a == "--truth-bdf-rtol") {
      o.truth_rtol = std::stod(bench::option_value(argc, argv, i));
      if (!(o.truth_rtol > 0 && o.truth_rtol < 1e-2))
        throw std::invalid_argument("--truth-bdf-rtol must be in (0, 1e-2)");
    } else if (a == "--test-seed") {
      o.test_seed = true;
    } else if (a == "--verbose") {
      o.verbose = true;
    } else if (a == "--contender-settled") {
      o.diagnosis.contender_settled = std::stod(bench::option_value(argc, argv, i));
    } else if (a == "--restart-span") {
      o.diagnosis.restart_span = std::stod(bench::option_value(argc, argv, i));
    } else if (a == "--progress") {
      o.progress = true;
    } else if (a == "--threads") {
      o.threads = std::stoi(bench::option_value(argc, argv, i));
    } else if (a == "--relinearizations") {
      o.diagnosis.relinearizations = std::stoi(bench::option_value(argc, argv, i));
    } else if (a == "--refinements") {
      o.diagnosis.refinements = std::stoi(bench::option_value(argc, argv, i));
    } else if (a == "--relinearize-gain") {
      o.diagnosis.relinearize_gain = std::stod(bench::option_value(argc, argv, i));
    } else if (a == "--contender-gain") {
      o.diagnosis.contender_gain = std::stod(bench::option_value(argc, argv, i));
    } else if (a == "--effects") {
      o.diagnosis.effects = bench::split(bench::option_value(argc, argv, i));
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  if (o.seeds < 1) throw std::invalid_argument("--seeds must be >= 1");
  if (o.test_seed) o.seeds = 1;
  o.diagnosis.validate();
  return o;
}

struct Row {
  int named = 0, runs = 0;
  double worst_fall = INFINITY, worst_zg_fit = 0, worst_zg_id = 0, seconds = 0, noise_ratio = 0;
  std::string misses;  // what was named where the hidden effect was not
};

void print_run(const std::string& name, std::uint64_t seed, const diagnose::Diagnosis& d) {
  std::fprintf(stderr, "%s seed %llu: baseline %.3g x the noise (gate %.3g, numerics %.3g); %s\n", name.c_str(),
               static_cast<unsigned long long>(seed), d.noise_ratio, d.noise_gate, d.numerics_ratio, d.summary.c_str());
  for (const auto& e : d.ranking) {
    std::fprintf(stderr,
                 "  %-28s explained %.6f residual/noise %.4g p %.3g significant %d plausible %d vs first %.3g\n",
                 e.effect.c_str(), e.explained_fraction, d.samples > 0 ? e.residual / d.samples : 0.0, e.p_value,
                 e.significant, e.plausible, e.versus_first_p);
    if (!e.note.empty()) std::fprintf(stderr, "    note: %s\n", e.note.c_str());
  }
  if (!d.ranking_note.empty()) std::fprintf(stderr, "  ranking note: %s\n", d.ranking_note.c_str());
  for (const auto& st : d.chain) {
    std::fprintf(stderr, "  chain: %s -> %.4g x the noise (p %.3g)\n", st.effect.c_str(), st.noise_ratio, st.p_value);
    for (const auto& p : st.parameters) {
      std::fprintf(stderr, "    %s = %.4g +- %.2g %s\n", p.name.c_str(), p.value, p.std, p.unit.c_str());
    }
    for (const auto& p : st.body) {
      std::fprintf(stderr, "    body %s = %+.4g +- %.2g %s (stated %.2g)\n", p.name.c_str(), p.value, p.std,
                   p.unit.c_str(), p.prior_std);
    }
  }
}

std::string noise_text(const Options& o) {
  std::string text;
  char t[120];
  if (o.noise_corner_hz > 0) {
    std::snprintf(t, sizeof t, ", the sensors' noise through a first-order low-pass at %g Hz", o.noise_corner_hz);
    text += t;
  }
  if (o.sample_rate_hz > 0) {
    std::snprintf(t, sizeof t, ", records at %g Hz", o.sample_rate_hz);
    text += t;
  }
  if (o.truth_rtol > 0) {
    std::snprintf(t, sizeof t, ", every record simulated by BDF at relative tolerance %g", o.truth_rtol);
    text += t;
  }
  return text;
}

rig::RigModel nominal_rig(const Options& o) {
  rig::RigModel m = o.quadrifilar ? test::noisy_quadrifilar() : test::noisy_trifilar();
  if (o.sample_rate_hz > 0) m.sensors.sample_rate_hz = o.sample_rate_hz;
  return m;
}

void run_case(const std::string& name, const Options& o, Row& row) {
  const rig::RigModel nominal = nominal_rig(o);
  rig::RigModel truth = test::case_truth(name, nominal);
  if (o.truth_rtol > 0) {
    truth.simulation.method = rig::IntegrationMethod::bdf;
    truth.simulation.relative_tolerance = o.truth_rtol;
  }
  const bool control = test::control_case(name);
  for (int k = 0; k < o.seeds; ++k) {
    const std::uint64_t seed = o.test_seed ? test::acceptance_seed(name) : o.first + static_cast<std::uint64_t>(k);
    const auto data =
        test::measure_histories(truth, o.test_seed ? seed : 1000 * seed + 17, o.noise_corner_hz, o.histories);
    const rig::RigModel start = test::users_model(nominal, data, seed);
    diagnose::DiagnosisOptions dopt = o.diagnosis;
    dopt.threads = o.threads;
    const auto t0 = bench::clock_type::now();
    if (o.progress) {
      dopt.progress = [&](const std::string& s) {
        std::fprintf(stderr, "%8.1f s  %s\n", bench::seconds_since(t0), s.c_str());
      };
    }
    const diagnose::Diagnosis d = diagnose::diagnose(start, test::record_pointers(data), {}, dopt);
    row.seconds += bench::seconds_since(t0);
    row.noise_ratio = std::max(row.noise_ratio, d.noise_ratio);
    ++row.runs;
    bool ok = false;
    if (control) {
      ok = !d.missing_effect;
    } else if (name == "two_effects") {
      int found = 0;
      for (const auto& st : d.chain) found += st.effect == "rod_length_error" || st.effect == "load_cell_gain";
      ok = found == 2 && d.chain.size() == 2;
    } else {
      ok = d.missing_effect && *d.missing_effect == name && d.chain.size() == 1;
    }
    row.named += ok;
    if (o.verbose) print_run(name, seed, d);
    if (!ok) {
      std::string named;
      for (const auto& st : d.chain) named += (named.empty() ? "" : "+") + st.effect;
      row.misses += (row.misses.empty() ? "" : "; ") + (named.empty() ? std::string("none") : named);
    }
    if (control || d.ranking.empty()) continue;
    const rig::RigModel fitted = test::with_found(start, d);
    const auto before = diagnose::compare_model(diagnose::ResponseModel(start), test::record_pointers(data), {}, {});
    const auto after = diagnose::compare_model(diagnose::ResponseModel(fitted), test::record_pointers(data), {}, {});
    const double fall = before.force_nrmse >= before.angle_nrmse ? before.force_nrmse / after.force_nrmse
                                                                 : before.angle_nrmse / after.angle_nrmse;
    row.worst_fall = std::min(row.worst_fall, fall);
    row.worst_zg_fit = std::max(row.worst_zg_fit, std::abs(fitted.body.cog.z() - truth.body.cog.z()));
    const double zg_id =
        after.identified ? std::abs(after.identified->properties.cog.z() - truth.body.cog.z()) : INFINITY;
    row.worst_zg_id = std::max(row.worst_zg_id, zg_id);
    if (o.verbose) {
      double stated = 0;
      for (const auto& p : d.body) stated = p.name == "cog_z" ? p.std : stated;
      std::fprintf(stderr, "  zG: fit %+.3f mm (std %.3f), identified %+.3f mm off the truth; fall %.3g\n",
                   1e3 * (fitted.body.cog.z() - truth.body.cog.z()), 1e3 * stated, 1e3 * zg_id, fall);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_diagnosis_seeds: %s\n", e.what());
    return 2;
  }
  if (o.cases.empty()) {
    o.cases = {"none", "below_noise"};
    const rig::RigModel nominal = nominal_rig(o);
    for (int k = 0; k < test::kHiddenEffects; ++k) {
      if (const auto e = test::hidden_effect(k, nominal)) o.cases.push_back(e->name());
    }
    o.cases.push_back("two_effects");
  }
  std::printf(
      "seeds %llu..%llu, %s, %d histories x 15 s per seed, the user's model (CoG +-3/+-3/+-7 mm, "
      "inertia from the rigid identification)%s\n\n",
      static_cast<unsigned long long>(o.first), static_cast<unsigned long long>(o.first + o.seeds - 1),
      o.quadrifilar ? "quadrifilar 250 kg (rods 2e7 N/m)" : "trifilar 200 kg", o.histories, noise_text(o).c_str());
  std::printf("| case | named | fall (worst) | zG fit mm (worst) | zG id mm (worst) | residual / noise (max) | "
              "diagnose s (mean) | named instead |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& name : o.cases) {
    Row row;
    try {
      run_case(name, o, row);
    } catch (const std::exception& e) {
      std::printf("| %s | failed: %s |\n", name.c_str(), e.what());
      std::fflush(stdout);
      continue;
    }
    const bool control = test::control_case(name);
    char fall[32] = "-", fit[32] = "-", id[32] = "-";
    if (!control) {
      std::snprintf(fall, sizeof fall, "%.1f", row.worst_fall);
      std::snprintf(fit, sizeof fit, "%.2f", 1e3 * row.worst_zg_fit);
      std::snprintf(id, sizeof id, "%.2f", 1e3 * row.worst_zg_id);
    }
    std::printf("| %s | %d of %d | %s | %s | %s | %.3g | %.0f | %s |\n", name.c_str(), row.named, row.runs, fall, fit,
                id, row.noise_ratio, row.seconds / std::max(row.runs, 1),
                row.misses.empty() ? "-" : row.misses.c_str());
    std::fflush(stdout);
  }
  return 0;
}
