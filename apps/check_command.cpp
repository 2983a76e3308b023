// rigflex check RIG.yaml [--out DIR]: the rig's swing and deformation modes
// at static equilibrium, the ratio of the first deformation frequency to the
// highest swing frequency, the verdict, where the strain energy sits and how
// much stiffer the dominant component must be, and the rigid algorithm's
// predicted error on a short virtual measurement. Writes DIR/check.json and the
// rig's modes and its assembly for ParaView (DIR/rig_modes.pvd, DIR/rig_assembly.vtu).
#include <cstdio>
#include <filesystem>
#include <optional>

#include "apps/commands.hpp"
#include "apps/work_estimate.hpp"
#include "identify/identification_rig.hpp"
#include "identify/predicted_error.hpp"
#include "io/atomic_file.hpp"
#include "io/integration_error.hpp"
#include "io/output_folder.hpp"
#include "io/rig_assembly_vtk.hpp"
#include "io/rig_reader.hpp"
#include "io/rig_vtk.hpp"
#include "report/check_json.hpp"
#include "rig/design_check.hpp"
#include "rig/equilibrium.hpp"

namespace rigflex::app {
namespace {

struct CheckArgs {
  std::string rig;
  std::string out;
  int predict_sets = 3;
  int predict_histories = 6;
  double predict_duration = 15.0;
  unsigned long long seed = 1;
  bool quiet = false;
};

void print_errors(const char* what, const identify::ErrorSummary& e) {
  std::printf("  %s: zG %+.2f mm (std %.2f mm); Jxx %+.2f %%, Jyy %+.2f %%, Jzz %+.2f %%; products <= %.2f %% of "
              "the largest moment\n",
              what, 1e3 * e.zG_mean_m, 1e3 * e.zG_std_m, 100 * e.moment_mean[0], 100 * e.moment_mean[1],
              100 * e.moment_mean[2], 100 * e.product_max);
}

void print_prediction(const identify::Prediction& p) {
  std::printf("predicted identification error (%d virtual set(s) x %d histories of %.3g s, noise on):\n", p.sets,
              p.histories, p.duration_s);
  if (p.rigid) print_errors("rigid algorithm", *p.rigid);
  if (p.from_flexibility) {
    print_errors("of it from flexibility (rigid - flexible)", *p.from_flexibility);
    std::printf("  against the rig's accuracy (zG 5 mm, moments 3 %%, products 1.5 %%, CoG in plane 3 mm): %.3g times "
                "it; by the error alone: %s\n",
                identify::accuracy_score(*p.from_flexibility), rig::to_string(p.verdict));
  }
  if (!p.note.empty()) std::printf("  note: %s\n", p.note.c_str());
}

// The one verdict and the one advice, after everything that weighs in.
void print_conclusion(const identify::CheckConclusion& c) {
  std::printf("verdict: %s (%s)\n", rig::to_string(c.verdict), c.reason.c_str());
  if (c.advice) std::printf("advice (%s): %s\n", c.advice_reason.c_str(), c.advice->message.c_str());
}

void print(const rig::CheckResult& r) {
  std::printf("%5s %12s  %-15s %8s %8s %8s\n", "mode", "f [Hz]", "kind", "fixed", "rods", "carrying");
  int k = 0;
  for (const auto& m : r.linearization.modes) {
    const double t = m.strain.total() > 0 ? m.strain.total() : 1.0;
    std::printf("%5d %12.5f  %-15s %8.3f %8.3f %8.3f\n", ++k, m.frequency_hz, rig::to_string(m.kind),
                m.strain.fixed_frame / t, m.strain.rods / t, m.strain.carrying_frame / t);
  }
  std::printf("(strain energy shares of each mode by component)\n");
  std::printf("swing frequencies:");
  for (double f : r.swing_frequencies_hz) std::printf(" %.4f", f);
  std::printf(" Hz\n");
  if (!r.first_deformation_frequency_hz) {
    std::printf("no deformation mode: frames and rods are rigid in this model\n");
    return;
  }
  std::printf("first deformation frequency f1 = %.4f Hz, ratio f1 / highest swing = %.3f\n",
              *r.first_deformation_frequency_hz, *r.ratio);
  std::printf("by the ratio alone: %s (>= 4 safe, 3-4 marginal, < 3 use the flexible algorithm)\n",
              rig::to_string(r.verdict));
  std::printf("strain energy in the first deformation mode: fixed frame %.1f %%, rods %.1f %%, carrying frame %.1f %%\n",
              100 * r.share_fixed_frame, 100 * r.share_rods, 100 * r.share_carrying_frame);
}

int run(const CheckArgs& a) {
  std::optional<io::OutputFolder> folder;
  if (!a.out.empty()) folder.emplace(a.out, "check");
  const io::RigReadOptions ro = frame_reduction_options("check", a.quiet);
  const rig::RigSpec spec = io::read_rig_spec(a.rig);
  const rig::RigModel model = io::resolve_rig(spec, ro);
  const rig::CheckResult r = [&] {
    try {
      return rig::design_check(model);
    } catch (const rig::NoEquilibrium& e) {
      throw io::no_equilibrium_error(a.rig, model, e.what());
    }
  }();
  print(r);
  std::optional<identify::Prediction> prediction;
  if (a.predict_sets > 0) {
    identify::VirtualStudyOptions o;
    o.sets = a.predict_sets;
    o.histories = a.predict_histories;
    o.duration_s = a.predict_duration;
    o.seed = a.seed;
    if (!a.quiet) {
      o.progress = [&](int set, int history) {
        std::fprintf(stderr, "check: virtual measurement set %d/%d, history %d/%d\n", set, o.sets, history,
                     o.histories);
      };
    }
    try {
      prediction = identify::predict_identification_error(model, o);
    } catch (const rig::IntegrationFailure& e) {
      throw io::integration_error(e, model, {a.rig});
    }
    print_prediction(*prediction);
  }
  const identify::CheckConclusion conclusion = identify::conclude_check(r, prediction);
  print_conclusion(conclusion);
  if (!a.out.empty()) {
    const std::filesystem::path out(a.out);
    std::filesystem::create_directories(out);
    io::FileBatch batch;
    batch.add_text(out / "check.json", report::check_json(model, r, prediction, conclusion).dump(2) + "\n");
    const rig::RigSystem rig(model);
    io::add_rig_mode_files(batch, out, rig, r.linearization);
    io::add_rig_assembly_file(batch, out / "rig_assembly.vtu", rig, r.linearization.equilibrium.configuration,
                              io::assembly_frames(spec));
    folder->commit(batch);
    std::printf("wrote %s/check.json, rig_modes.pvd (%zu modes) and rig_assembly.vtu (frames, rods and body at rest)\n",
                a.out.c_str(), r.linearization.modes.size());
  }
  return 0;
}

}  // namespace

void add_check_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("check", "Design check: first deformation frequency against the swing frequencies");
  auto a = std::make_shared<CheckArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("--out", a->out, "folder for check.json and the rig's mode shapes");
  cmd->add_option("--predict-sets", a->predict_sets,
                  "virtual measurement sets for the predicted identification error (0: skip)")
      ->check(non_negative());
  cmd->add_option("--predict-histories", a->predict_histories, "histories per virtual set")->check(positive());
  cmd->add_option("--predict-duration", a->predict_duration, "record length of a virtual history [s]")
      ->check(positive());
  cmd->add_option("--seed", a->seed, "seed of the virtual releases and noise");
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
