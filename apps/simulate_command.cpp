// rigflex simulate RIG.yaml [--sets K] [--histories 6] [--duration 15]
//   [--seed S] --out DIR: a virtual measurement of the rig, written as
// DIR/set<k>/h<j>.csv in the form of shared/spec/rig-conventions.md.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "apps/commands.hpp"
#include "apps/work_estimate.hpp"
#include "io/atomic_file.hpp"
#include "io/integration_error.hpp"
#include "io/measurement_csv.hpp"
#include "io/output_folder.hpp"
#include "io/rig_reader.hpp"
#include "rig/equilibrium.hpp"
#include "rig/simulation.hpp"

namespace rigflex::app {
namespace {

struct SimulateArgs {
  std::string rig;
  int sets = 1;
  int histories = 6;
  double duration = 15.0;
  unsigned long long seed = 1;
  std::string out;
  bool quiet = false;
};

// The record as its file shows it: how the run was made, then how the history was (the push).
rig::Record file_record(const rig::Record& h, const rig::RigModel& model, const SimulateArgs& a, int set,
                        int history) {
  rig::Record t = h;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.10g", model.sensors.sample_rate_hz);
  t.provenance.comments = {{"source", "rigflex simulate"},
                           {"rig", model.name},
                           {"sample_rate_hz", rate},
                           {"seed", std::to_string(a.seed)},
                           {"set", std::to_string(set)},
                           {"history", std::to_string(history)}};
  for (const auto& c : h.provenance.comments) t.provenance.comments.push_back(c);
  return t;
}

int run(const SimulateArgs& a) {
  io::OutputFolder folder(a.out, "simulate");
  const auto start = std::chrono::steady_clock::now();
  const io::RigReadOptions ro = frame_reduction_options("simulate", a.quiet);
  const rig::RigModel model = io::resolve_rig(io::read_rig_spec(a.rig), ro);
  const rig::RigSystem rig(model);
  rig::MeasurementOptions o;
  o.sets = a.sets;
  o.histories = a.histories;
  o.duration_s = a.duration;
  o.seed = a.seed;
  if (!a.quiet) {
    o.progress = [&](int set, int history) {
      std::fprintf(stderr, "simulate: set %d/%d, history %d/%d\n", set, a.sets, history, a.histories);
    };
  }
  const auto sets = [&] {
    try {
      return rig::simulate_measurement(rig, o);
    } catch (const rig::NoEquilibrium& e) {
      throw io::no_equilibrium_error(a.rig, model, e.what());
    } catch (const rig::IntegrationFailure& e) {
      throw io::integration_error(e, model, {a.rig});
    }
  }();
  io::FileBatch batch;
  const std::filesystem::path out(a.out);
  for (size_t k = 0; k < sets.size(); ++k) {
    for (size_t j = 0; j < sets[k].size(); ++j) {
      const auto file = out / ("set" + std::to_string(k + 1)) / ("h" + std::to_string(j + 1) + ".csv");
      std::filesystem::create_directories(file.parent_path());
      batch.add_text(file, io::format_record_csv(
                               file_record(sets[k][j], model, a, static_cast<int>(k + 1), static_cast<int>(j + 1))));
    }
  }
  folder.commit(batch);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("rig: %s, %d rods, %.6g kg, effects:", model.name.c_str(), rig.rods(), model.body.mass);
  if (model.effects.empty()) std::printf(" none");
  for (const auto& e : model.effects) std::printf(" %s", e->name());
  std::printf("\nwrote %d set(s) x %d histories of %.6g s at %.6g Hz to %s (%.2f s)\n", a.sets, a.histories,
              a.duration, model.sensors.sample_rate_hz, a.out.c_str(), seconds);
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("simulate", "Simulate the rig's release and free swing; write measurement CSVs");
  auto a = std::make_shared<SimulateArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("--sets", a->sets, "measurement sets (repeated measurements)")->check(positive());
  cmd->add_option("--histories", a->histories, "time histories per set")->check(positive());
  cmd->add_option("--duration", a->duration, "record length after release [s]")->check(positive());
  cmd->add_option("--seed", a->seed, "seed of the pushes and the sensor noise");
  cmd->add_option("--out", a->out, "output folder: DIR/set<k>/h<j>.csv")->required();
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
