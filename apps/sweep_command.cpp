// rigflex sweep RIG.yaml [--mass-scale 0.1:1:10] [--stiffness-scale 1:10:10]
//   [--sets 9] [--histories 6] [--duration 15] [--seed S] [--threads N] --out DIR:
// identification error against mass and stiffness (identify/sweep.hpp), as
// DIR/sweep.csv, DIR/sweep.json and the report DIR/sweep.html.
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/commands.hpp"
#include "apps/work_estimate.hpp"
#include "identify/sweep.hpp"
#include "io/atomic_file.hpp"
#include "io/output_folder.hpp"
#include "io/rig_reader.hpp"
#include "report/reports.hpp"
#include "report/sweep_json.hpp"

namespace rigflex::app {
namespace {

struct SweepArgs {
  std::string rig;
  std::string mass_scale = "0.1:1:10", stiffness_scale = "1:10:10";
  int sets = 9, histories = 6;
  double duration = 15.0;
  unsigned long long seed = 1;
  int threads = 0;
  std::string out;
  bool quiet = false;
};

identify::ScaleRange parse_range(const std::string& text, const std::string& option) {
  identify::ScaleRange r;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> r.start >> c1 >> r.stop >> c2 >> r.count) || c1 != ':' || c2 != ':' || !in.eof()) {
    throw std::invalid_argument(option + ": expected start:stop:count (for example 0.1:1:10), got '" + text + "'");
  }
  r.validate(option);
  return r;
}

int run(const SweepArgs& a) {
  io::OutputFolder folder(a.out, "sweep");
  const rig::RigModel model = io::resolve_rig(io::read_rig_spec(a.rig), frame_reduction_options("sweep", a.quiet));
  identify::SweepOptions o;
  o.mass = parse_range(a.mass_scale, "--mass-scale");
  o.stiffness = parse_range(a.stiffness_scale, "--stiffness-scale");
  o.study.sets = a.sets;
  o.study.histories = a.histories;
  o.study.duration_s = a.duration;
  o.study.seed = a.seed;
  o.threads = a.threads;
  if (!a.quiet) o.progress = [](int done, int total) { std::fprintf(stderr, "sweep: point %d/%d\n", done, total); };
  const auto points = identify::sweep(model, o);

  std::printf("%-9s %7s %8s %7s %12s %10s %12s %10s %s\n", "kind", "scale", "f1 [Hz]", "ratio", "rigid zG mm",
              "rigid Jyy%", "flex zG mm", "flex Jyy%", "");
  for (const auto& p : points) {
    auto mm = [](const std::optional<identify::ErrorSummary>& e) { return e ? 1e3 * e->zG_mean_m : NAN; };
    auto pc = [](const std::optional<identify::ErrorSummary>& e) { return e ? 100 * e->moment_mean[1] : NAN; };
    std::printf("%-9s %7.3g %8.3f %7.2f %12.2f %10.3f %12.2f %10.3f %s\n", identify::to_string(p.kind), p.scale,
                p.f1_hz.value_or(NAN), p.ratio.value_or(NAN), mm(p.rigid), pc(p.rigid), mm(p.flexible),
                pc(p.flexible), p.failure.c_str());
  }
  report::SweepSettings settings;
  settings.mass_scale = a.mass_scale;
  settings.stiffness_scale = a.stiffness_scale;
  settings.sets = a.sets;
  settings.histories = a.histories;
  settings.duration_s = a.duration;
  settings.seed = a.seed;
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  io::FileBatch batch;
  batch.add_text(out / "sweep.csv", report::sweep_csv(points));
  batch.add_text(out / "sweep.json", report::sweep_json(model.name, settings, points).dump(2) + "\n");
  batch.add_text(out / "sweep.html", report::sweep_html(model.name, points).html());
  folder.commit(batch);
  std::printf("(errors: identified - true; zG mean over the sets in mm, Jyy mean relative in %%)\nwrote %s/sweep.csv, sweep.json and sweep.html\n",
              a.out.c_str());
  return 0;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("sweep", "Identification error against mass and stiffness scale (virtual measurements)");
  auto a = std::make_shared<SweepArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("--mass-scale", a->mass_scale, "start:stop:count, log-spaced (mass and inertia scale)");
  cmd->add_option("--stiffness-scale", a->stiffness_scale, "start:stop:count, log-spaced (frames and rods)");
  cmd->add_option("--sets", a->sets, "measurement sets per point")->check(positive());
  cmd->add_option("--histories", a->histories, "histories per set")->check(positive());
  cmd->add_option("--duration", a->duration, "record length [s]")->check(positive());
  cmd->add_option("--seed", a->seed, "seed of releases and noise");
  cmd->add_option("--threads", a->threads, "points in parallel (0: all cores)")->check(thread_count());
  cmd->add_option("--out", a->out, "output folder")->required();
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
