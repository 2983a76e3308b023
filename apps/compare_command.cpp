// rigflex compare RIG.yaml DATA... --out DIR [--effects FILE]... [--reference FILE]
//   [--study DIR] [--fit-window S] [--threads N] [--hold-body] [--quiet]:
// the model against measured histories: the swing state fitted to each
// record's first seconds, the body's mass properties (and any parameter
// whose uncertainty the rig file states) refitted with the swing states
// unless --hold-body, the record simulated, residuals per channel and
// where they concentrate, the mass properties identified with the model's
// algorithm; DIR/compare.json, DIR/model/*.csv (the model's signals, in the
// measurement format), and, with --study, the error of this model version
// next to the earlier ones.
#include <cstdio>
#include <filesystem>

#include "apps/commands.hpp"
#include "apps/measured_model.hpp"
#include "apps/parameter_table.hpp"
#include "diagnose/model_comparison.hpp"
#include "io/atomic_file.hpp"
#include "io/mass_record.hpp"
#include "io/measurement_csv.hpp"
#include "io/output_folder.hpp"
#include "io/rig_reader.hpp"
#include "report/compare_json.hpp"
#include "report/reports.hpp"
#include "report/study.hpp"
#include "rig/equilibrium.hpp"

namespace rigflex::app {
namespace {

struct CompareArgs {
  std::string rig;
  std::vector<std::string> data, effects;
  std::string reference, study, out;
  double fit_window = 0;
  int threads = 0;
  bool quiet = false, hold_body = false;
};

rig::Record model_history(const diagnose::HistoryComparison& h, int rods, const std::string& label) {
  rig::Record t;
  t.provenance.comments = {{"source", "rigflex compare: model " + label}, {"measurement", h.source}};
  t.t = h.t();
  t.force = h.model.leftCols(rods);
  t.alpha = h.model.middleCols(rods, rods);
  t.beta = h.model.rightCols(rods);
  return t;
}

// The refit of the model's own parameters: what to correct in the rig file.
void print_model_fit(const diagnose::ModelComparison& c) {
  if (!c.model_fit) return;
  const diagnose::ModelParameterFit& f = *c.model_fit;
  if (!f.credible) {
    std::printf(
        "%s: as the rig file gives it (refitted, the model stays at %.3g x the noise; there the offsets "
        "would absorb a missing effect: run rigflex diagnose)\n",
        fitted_parameters_label(f.parameters).c_str(), f.noise_ratio);
    return;
  }
  std::printf(
      "%s refitted (offset from the rig file, its std, the stated std); residual / noise %.3g -> %.3g, "
      "force NRMSE %.4f as stated:\n",
      fitted_parameters_label(f.parameters).c_str(), f.noise_ratio_as_stated, f.noise_ratio,
      c.as_stated ? c.as_stated->force : 0.0);
  print_parameter_table(f.parameters);
  for (const auto& p : f.off) std::printf("model parameter off: %s\n", diagnose::describe_off(p).c_str());
}

void print_table(const diagnose::ModelComparison& c) {
  std::printf("%-8s %10s %10s %14s\n", "channel", "NRMSE", "raw NRMSE", "residual/noise");
  for (size_t i = 0; i < c.channels.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    std::printf("%-8s %10.4f %10.4f %14.2f\n", c.channels[i].c_str(), c.nrmse(k), c.raw_nrmse(k),
                c.analysis.noise_ratio(k));
  }
  std::printf("overall NRMSE %.4f (forces %.4f, angles %.4f) in the swing band; raw %.4f (forces %.4f)\n",
              c.overall_nrmse, c.force_nrmse, c.angle_nrmse, c.raw_overall_nrmse, c.raw_force_nrmse);
  std::printf("trend %+.4f per s; extra decay (measured - model) %+.4f 1/s\n", c.analysis.trend_slope,
              c.analysis.extra_decay_rate);
  for (const auto& s : c.analysis.correlations) {
    std::printf("residual vs %-16s largest correlation %+.2f (%s)\n", s.state.c_str(), s.largest, s.channel.c_str());
  }
  print_model_fit(c);
  if (c.identified) {
    const auto& p = c.identified->properties;
    std::printf("identified (%s): m %.2f kg, CoG (%.4f, %.4f, %.4f) m\n", identify::to_string(c.algorithm), p.mass,
                p.cog.x(), p.cog.y(), p.cog.z());
  } else if (!c.identification_error.empty()) {
    std::printf("identification: %s\n", c.identification_error.c_str());
  }
}

// The model's history beside each measured one: "<set folder>_<file>", so
// h1.csv of set1 and of set2 do not collide (an index where folders share a name).
std::string model_file_name(const MeasuredModel& mm, size_t i) {
  auto name = [&](size_t k) {
    const std::filesystem::path file(mm.records[k].provenance.file);
    return file.parent_path().filename().string() + "_" + file.filename().string();
  };
  const std::string mine = name(i);
  for (size_t k = 0; k < mm.records.size(); ++k) {
    if (k != i && name(k) == mine) return std::to_string(i + 1) + "_" + mine;
  }
  return mine;
}

int compare_with(MeasuredModel& mm, const CompareArgs& a, io::OutputFolder& folder) {
  report::CompareContext ctx;
  ctx.rig = mm.model.name;
  ctx.model_label = mm.label;
  ctx.model_effects = mm.effect_names;
  if (!a.reference.empty()) ctx.reference = io::read_mass_record(a.reference);

  diagnose::ModelComparisonOptions o;
  if (a.fit_window > 0) o.compare.fit_window_s = a.fit_window;
  o.threads = a.threads;
  o.fit_model = !a.hold_body;
  if (!a.quiet) {
    o.progress = [](int done, int total) { std::fprintf(stderr, "compare: history %d/%d\n", done, total); };
    o.fit_progress = [](const std::string& s) { std::fprintf(stderr, "compare: %s\n", s.c_str()); };
  }
  std::unique_ptr<diagnose::ResponseModel> model;
  try {
    model = std::make_unique<diagnose::ResponseModel>(mm.model);
  } catch (const rig::NoEquilibrium& e) {
    throw io::no_equilibrium_error(a.rig, mm.model, e.what());
  }
  diagnose::ModelComparison c;
  try {
    c = diagnose::compare_model(*model, mm.pointers(), mm.sources(), o);
  } catch (const rig::RecordError& e) {
    rethrow_record_error(mm, e);
  }
  for (const auto& w : c.warnings) std::fprintf(stderr, "compare: warning: %s\n", w.c_str());
  print_table(c);

  nlohmann::ordered_json j = report::compare_json(c, ctx);
  std::vector<report::StudyEntry> entries;
  report::StudyEntry study_entry;
  if (!a.study.empty()) {
    report::StudyEntry& e = study_entry;
    e.label = mm.label;
    // A version: the model files, the options that change the errors, and the data compared with.
    std::vector<std::filesystem::path> inputs = mm.model_files;
    for (const auto& r : mm.records) inputs.emplace_back(r.provenance.file);
    e.fingerprint = report::model_fingerprint(
        inputs, "fit_window=" + std::to_string(o.compare.fit_window_s) + (a.hold_body ? " hold_body" : ""));
    e.effects = mm.effect_names;
    e.overall_nrmse = c.overall_nrmse;
    e.force_nrmse = c.force_nrmse;
    e.angle_nrmse = c.angle_nrmse;
    for (size_t i = 0; i < c.channels.size(); ++i) e.nrmse[c.channels[i]] = c.nrmse(static_cast<Eigen::Index>(i));
    if (c.identified) e.identified_cog_z = c.identified->properties.cog.z();
    entries = report::study_with(a.study, e);
    std::printf("study %s:\n%-8s %-12s %-12s %s\n", a.study.c_str(), "version", "overall", "forces", "model");
    for (const auto& x : entries) {
      std::printf("%-8d %-12.4f %-12.4f %s%s\n", x.version, x.overall_nrmse, x.force_nrmse, x.label.c_str(),
                  x.fingerprint == e.fingerprint ? "  <- this run" : "");
    }
    j["study"] = report::study_versions_json(entries, e.fingerprint);
  }

  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out / "model");
  io::FileBatch batch;
  batch.add_text(out / "compare.json", j.dump(2) + "\n");
  batch.add_text(out / "compare.html", report::compare_report(c, ctx, entries).html());
  const int rods = mm.model.geometry.rod_count();
  for (size_t i = 0; i < c.histories.size(); ++i) {
    const rig::Record th = model_history(c.histories[i], rods, mm.label);
    batch.add(out / "model" / model_file_name(mm, i), [th](const std::filesystem::path& p) { io::write_record_csv(p, th); });
  }
  folder.commit(batch);
  // The study is written once the outputs are: a failed run leaves no entry.
  if (!a.study.empty()) report::record_in_study(a.study, study_entry);
  std::printf("wrote %s/compare.json, %s/compare.html and %zu model histories in %s/model\n", a.out.c_str(),
              a.out.c_str(), c.histories.size(), a.out.c_str());
  return 0;
}

int run(const CompareArgs& a) {
  io::OutputFolder folder(a.out, "compare");
  MeasuredModel mm = read_measured_model(a.rig, a.effects, a.data, a.quiet, "compare");
  return run_on_measured_model(mm, [&] { return compare_with(mm, a, folder); });
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("compare", "Compare the rig model with measured free swings");
  auto a = std::make_shared<CompareArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("data", a->data, "measurement files or set folders")->required();
  cmd->add_option("--effects", a->effects, "YAML file with an `effects:` block added to the model (e.g. from diagnose)");
  cmd->add_option("--reference", a->reference, "static reference mass properties record");
  cmd->add_option("--study", a->study, "study folder: keeps every model version's errors (study.json)");
  cmd->add_option("--fit-window", a->fit_window, "seconds at the start of each record the swing state is fitted to")
      ->check(positive());
  cmd->add_option("--threads", a->threads, "histories compared in parallel (0: all cores)")->check(thread_count());
  cmd->add_option("--out", a->out, "output folder")->required();
  cmd->add_flag("--hold-body", a->hold_body,
                "compare the body (and every parameter with a stated uncertainty) as the rig file gives it, not "
                "refitted");
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
