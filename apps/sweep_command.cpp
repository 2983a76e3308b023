// rigflex sweep RIG.yaml [--mass-scale 0.1:1:10] [--stiffness-scale 1:10:10]
//   [--sets 9] [--histories 6] [--duration 15] [--seed S] [--threads N] --out DIR:
// identification error against mass and stiffness (rig/sweep.hpp), as
// DIR/sweep.csv, DIR/sweep.json and the report DIR/sweep.html.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/commands.hpp"
#include "report/reports.hpp"
#include "io/atomic_file.hpp"
#include "io/rig_reader.hpp"
#include "identify/sweep.hpp"

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

std::string number(const std::optional<double>& v) {
  if (!v) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", *v);
  return b;
}

std::string csv(const std::vector<identify::SweepPoint>& points) {
  std::string out =
      "kind,scale,f1_hz,swing_max_hz,ratio,rigid_zG_mean_m,rigid_zG_std_m,rigid_Jyy_mean,rigid_Jyy_std,"
      "flexible_zG_mean_m,flexible_zG_std_m,flexible_Jyy_mean,flexible_Jyy_std,failure\n";
  for (const auto& p : points) {
    out += std::string(identify::to_string(p.kind)) + "," + number(p.scale) + "," + number(p.f1_hz) + "," +
           number(p.swing_max_hz) + "," + number(p.ratio);
    for (const auto* e : {&p.rigid, &p.flexible}) {
      if (*e) {
        out += "," + number((*e)->zG_mean_m) + "," + number((*e)->zG_std_m) + "," + number((*e)->moment_mean[1]) +
               "," + number((*e)->moment_std[1]);
      } else {
        out += ",,,,";
      }
    }
    std::string why = p.failure;
    for (char& c : why) {
      if (c == ',' || c == '\n') c = ';';
    }
    out += "," + why + "\n";
  }
  return out;
}

nlohmann::ordered_json errors_json(const std::optional<identify::ErrorSummary>& e) {
  if (!e) return nullptr;
  return {{"sets", e->sets},
          {"zG_mean_m", e->zG_mean_m},
          {"zG_std_m", e->zG_std_m},
          {"moment_mean", e->moment_mean},
          {"moment_std", e->moment_std},
          {"Jyy_mean", e->moment_mean[1]},
          {"Jyy_std", e->moment_std[1]},
          {"product_max_of_largest", e->product_max},
          {"cog_in_plane_max_m", e->cog_in_plane_max_m}};
}

nlohmann::ordered_json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

int run(const SweepArgs& a) {
  const rig::RigModel model = io::read_rig(a.rig);
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
  nlohmann::ordered_json pts = nlohmann::ordered_json::array();
  for (const auto& p : points) {
    auto mm = [](const std::optional<identify::ErrorSummary>& e) { return e ? 1e3 * e->zG_mean_m : NAN; };
    auto pc = [](const std::optional<identify::ErrorSummary>& e) { return e ? 100 * e->moment_mean[1] : NAN; };
    std::printf("%-9s %7.3g %8.3f %7.2f %12.2f %10.3f %12.2f %10.3f %s\n", identify::to_string(p.kind), p.scale,
                p.f1_hz.value_or(NAN), p.ratio.value_or(NAN), mm(p.rigid), pc(p.rigid), mm(p.flexible),
                pc(p.flexible), p.failure.c_str());
    pts.push_back({{"kind", identify::to_string(p.kind)},
                   {"scale", p.scale},
                   {"f1_hz", optional_json(p.f1_hz)},
                   {"swing_max_hz", optional_json(p.swing_max_hz)},
                   {"ratio", optional_json(p.ratio)},
                   {"rigid", errors_json(p.rigid)},
                   {"flexible", errors_json(p.flexible)},
                   {"failure", p.failure.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p.failure)}});
  }
  nlohmann::ordered_json j;
  j["rig"] = model.name;
  j["mass_scale"] = a.mass_scale;
  j["stiffness_scale"] = a.stiffness_scale;
  j["sets"] = a.sets;
  j["histories"] = a.histories;
  j["duration_s"] = a.duration;
  j["seed"] = a.seed;
  j["points"] = pts;
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  io::FileBatch batch;
  batch.add_text(out / "sweep.csv", csv(points));
  batch.add_text(out / "sweep.json", j.dump(2) + "\n");
  batch.add_text(out / "sweep.html", report::sweep_html(model.name, points).html());
  batch.commit();
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
  cmd->add_option("--threads", a->threads, "points in parallel (0: all cores)");
  cmd->add_option("--out", a->out, "output folder")->required();
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
