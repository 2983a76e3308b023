// rigflex diagnose RIG.yaml DATA... --out DIR [--effects FILE]... [--only NAMES]
//   [--threads N] [--max-effects N] [--period-tolerance E] [--rank-all] [--quiet]:
// which effect of the catalogue the model misses: each one the model lacks
// fitted to the measurements with every history's swing state, ranked by
// the share of the residual it explains; DIR/diagnosis.json, and per effect
// DIR/effects/<effect>.yaml with the fitted values, ready for
// `rigflex compare --effects` or to paste into the rig file; where an effect
// is missing, DIR/effects/found.yaml with every effect of the chain (the
// missing one, then each further one found with it) refitted together.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/commands.hpp"
#include "apps/measured_model.hpp"
#include "apps/parameter_table.hpp"
#include "diagnose/diagnosis.hpp"
#include "io/atomic_file.hpp"
#include "io/effects_file.hpp"
#include "io/output_folder.hpp"
#include "io/rig_reader.hpp"
#include "report/compare_json.hpp"
#include "report/reports.hpp"
#include "rig/equilibrium.hpp"

namespace rigflex::app {
namespace {

struct DiagnoseArgs {
  std::string rig;
  std::vector<std::string> data, effects, only;
  std::string out;
  double fit_window = 0;
  int threads = 0, max_effects = 3;
  bool quiet = false, rank_all = false;
  double period_tolerance = diagnose::DiagnosisOptions{}.period_tolerance;
};

// The fitted effect as an effects file, saying how well it fits and what
// to add to the model instead.
std::string effects_file_text(const diagnose::EffectFit& e) {
  std::ostringstream fitted;
  fitted << "Fitted by rigflex diagnose: explains " << e.explained_fraction * 100 << " % of the residual"
         << (e.significant ? " (significant)" : " (not significant)") << (e.plausible ? "" : "; IMPLAUSIBLE values")
         << ".";
  return io::effects_file_text({fitted.str(), e.advice + "."}, e.rig_block);
}

// The verdict's model: the chain's effects, or the model as it is.
std::string verdict_model(const diagnose::Diagnosis& d) {
  std::string names;
  for (const auto& st : d.chain) names += (names.empty() ? "" : " + ") + st.effect;
  return names.empty() ? "the model as it is" : names;
}

// Every effect of the chain as its last step refitted them.
std::string found_file_text(const diagnose::Diagnosis& d) {
  const diagnose::ChainStep& last = d.chain.back();
  char fitted[200];
  std::snprintf(fitted, sizeof fitted, "Fitted by rigflex diagnose: %s, refitted together; residual %.3g x the noise "
                "(%.3g x without them).", verdict_model(d).c_str(), last.noise_ratio, d.noise_ratio);
  return io::effects_file_text({fitted}, last.rig_block);
}

// The body's offsets from the rig file fitted with the verdict's model: what
// to correct in the rig file's `body` (those marked "off" lie beyond what
// its `uncertainty` states).
void print_body(const diagnose::Diagnosis& d) {
  if (d.body.empty()) {
    const double misfit = d.chain.empty() ? d.noise_ratio : d.chain.back().noise_ratio;
    std::printf("body: as the rig file gives it (the fit with %s stays at %.3g x the noise; there the body's offsets "
                "would absorb the model's remaining error)\n",
                verdict_model(d).c_str(), misfit);
    return;
  }
  std::printf("%s fitted with %s (offset from the rig file, its std, the stated std):\n",
              fitted_parameters_label(d.body).c_str(), verdict_model(d).c_str());
  print_parameter_table(d.body);
}

int diagnose_with(MeasuredModel& mm, const DiagnoseArgs& a, io::OutputFolder& folder) {
  diagnose::DiagnosisOptions o;
  if (a.fit_window > 0) o.compare.fit_window_s = a.fit_window;
  o.threads = a.threads;
  o.effects = a.only;
  o.max_effects = a.max_effects;
  o.rank_at_noise = a.rank_all;
  o.period_tolerance = a.period_tolerance;
  if (!a.quiet) o.progress = [](const std::string& s) { std::fprintf(stderr, "diagnose: %s\n", s.c_str()); };
  try {
    o.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--only: ") + e.what());
  }
  diagnose::Diagnosis d;
  try {
    d = diagnose::diagnose(mm.model, mm.pointers(), mm.sources(), o);
  } catch (const rig::NoEquilibrium& e) {
    throw io::no_equilibrium_error(a.rig, mm.model, e.what());
  } catch (const rig::RecordError& e) {
    rethrow_record_error(mm, e);
  }
  if (!d.ranking.empty()) {
    std::printf("%-28s %10s %12s %11s %9s %11s\n", "effect", "explained", "significant", "plausible", "p-value",
                "vs first p");
  }
  for (const auto& e : d.ranking) {
    std::printf("%-28s %9.4f%% %12s %11s %9.2g %11.2g\n", e.effect.c_str(), 100 * e.explained_fraction,
                e.significant ? "yes" : "no", e.plausible ? "yes" : "no", e.p_value, e.versus_first_p);
  }
  if (!d.ranking_note.empty()) std::printf("%s\n", d.ranking_note.c_str());
  std::printf("%s (baseline residual %.2f x the noise)\n", d.summary.c_str(), d.noise_ratio);
  print_body(d);
  if (d.missing_effect) {
    for (const auto& e : d.ranking) {
      if (e.effect != *d.missing_effect) continue;
      std::printf("fitted:\n%s", e.rig_block.c_str());
      std::printf("to capture it properly: %s\n", e.advice.c_str());
    }
  }
  if (d.chain.size() > 1 || !d.after_chain.empty()) {
    std::printf("chain: the model as it is %.3g x the noise", d.noise_ratio);
    for (const auto& st : d.chain) std::printf(" -> + %s %.3g x", st.effect.c_str(), st.noise_ratio);
    std::printf("%s\n", d.after_chain.empty() ? "" : " (nothing further significant)");
  }
  if (!d.chain_note.empty()) std::printf("%s\n", d.chain_note.c_str());
  report::CompareContext ctx;
  ctx.rig = mm.model.name;
  ctx.model_label = mm.label;
  ctx.model_effects = mm.effect_names;
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out / "effects");
  io::FileBatch batch;
  batch.add_text(out / "diagnosis.json", report::diagnosis_json(d, ctx).dump(2) + "\n");
  batch.add_text(out / "diagnosis.html", report::diagnosis_report(d, ctx, &d.baseline_analysis).html());
  // A file per effect that the fit made an effect of (a compliance fitted to zero is none).
  for (const auto& e : d.ranking) {
    if (!e.rig_block.empty()) batch.add_text(out / "effects" / (e.effect + ".yaml"), effects_file_text(e));
  }
  if (!d.chain.empty() && !d.chain.back().rig_block.empty()) {
    batch.add_text(out / "effects" / "found.yaml", found_file_text(d));
  }
  folder.commit(batch);
  std::printf("wrote %s/diagnosis.json, %s/diagnosis.html and the fitted effects in %s/effects\n", a.out.c_str(),
              a.out.c_str(), a.out.c_str());
  return 0;
}

int run(const DiagnoseArgs& a) {
  io::OutputFolder folder(a.out, "diagnose");
  MeasuredModel mm = read_measured_model(a.rig, a.effects, a.data, a.quiet, "diagnose");
  return run_on_measured_model(mm, [&] { return diagnose_with(mm, a, folder); });
}

}  // namespace

void add_diagnose_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("diagnose", "Find the physical effect the rig model misses");
  auto a = std::make_shared<DiagnoseArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("data", a->data, "measurement files or set folders")->required();
  cmd->add_option("--effects", a->effects, "YAML file with an `effects:` block added to the model first");
  cmd->add_option("--only", a->only, "test only these effects (comma separated)")->delimiter(',');
  cmd->add_option("--fit-window", a->fit_window, "seconds at the start of each record the swing state is first fitted to")
      ->check(positive());
  cmd->add_option("--threads", a->threads, "threads (0: all cores)")->check(thread_count());
  cmd->add_option("--max-effects", a->max_effects, "effects the chain accepts at most (1: the missing one alone)")
      ->check(positive());
  cmd->add_option("--period-tolerance", a->period_tolerance,
                  "relative swing period error the records' simulator may have, allowed in the gate (0: records "
                  "from a real rig)")
      ->check(CLI::Range(0.0, 0.0099));
  cmd->add_option("--out", a->out, "output folder")->required();
  cmd->add_flag("--rank-all", a->rank_all,
                "fit and rank every candidate even where the model reaches the noise (none can be significant)");
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
