// rigflex identify RIG.yaml DATA... [--algorithm rigid|flexible|both]
//   [--effects FILE]... [--reduced DIR]... [--static-cog X,Y[,Z]] [--tare FILE] [--reference FILE]
//   [--mass KG] [--window S] [--degree N] [--threads N] --out DIR:
// mass properties from measured free swings, one least-squares solve per
// measurement set (and per history alone, for the test-to-test scatter),
// statistics over the sets, DIR/identification.json.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "apps/commands.hpp"
#include "apps/measured_model.hpp"
#include "apps/work_estimate.hpp"
#include "identify/identification.hpp"
#include "io/atomic_file.hpp"
#include "io/mass_record.hpp"
#include "io/measurement_csv.hpp"
#include "io/output_folder.hpp"
#include "io/reduced_export.hpp"
#include "io/reduced_layout.hpp"
#include "io/rig_reader.hpp"
#include "report/identification_report.hpp"
#include "report/identify_sets.hpp"
#include "report/reports.hpp"
#include "rig/effects.hpp"
#include "rig/frame_models.hpp"

namespace rigflex::app {
namespace {

struct IdentifyArgs {
  std::string rig;
  std::vector<std::string> data;
  std::string algorithm = "rigid";
  std::vector<std::string> effects, reduced;
  std::vector<double> static_cog;
  std::string tare, reference;
  double mass = 0;
  double window = 0, degree = 0;
  int threads = 0;
  std::string out;
  bool quiet = false;
};

// A reduced frame from `rigflex reduce` replaces the rig file's model of the
// frame it fits: grounded -> fixed frame, free-free -> carrying frame.
void use_reduced(rig::RigModel& model, const std::filesystem::path& dir) {
  const reduction::ReducedFrame frame = io::read_reduced_frame(dir);
  const std::string file = (dir / io::reduced_layout::kJsonFile).string();
  std::shared_ptr<rig::Effect> effect;
  try {
    if (frame.support == reduction::FrameSupport::grounded) {
      effect = std::make_shared<rig::FixedFrameFlexibility>(rig::fixed_frame_model(frame, model.geometry));
    } else {
      effect = std::make_shared<rig::CarryingFrameFlexibility>(rig::carrying_frame_model(frame, model.geometry));
    }
  } catch (const std::invalid_argument& e) {
    throw io::InputError(file, 0, "interface_nodes", std::string("does not match the rig's joints: ") + e.what());
  }
  std::erase_if(model.effects, [&](const auto& e) { return std::string(e->name()) == effect->name(); });
  model.effects.push_back(effect);
}

identify::IdentificationOptions options_from(const IdentifyArgs& a) {
  identify::IdentificationOptions o;
  if (a.window > 0) o.differentiation.window_s = a.window;
  if (a.degree > 0) o.differentiation.degree = static_cast<int>(a.degree);
  if (a.static_cog.size() == 2) {
    o.cog_constraint = identify::CogConstraint::in_plane;
    o.imposed_cog = rig::Vec3(a.static_cog[0], a.static_cog[1], 0.0);
  } else if (a.static_cog.size() == 3) {
    o.cog_constraint = identify::CogConstraint::full;
    o.imposed_cog = rig::Vec3(a.static_cog[0], a.static_cog[1], a.static_cog[2]);
  } else if (!a.static_cog.empty()) {
    throw std::invalid_argument("--static-cog: expected X,Y or X,Y,Z in metres");
  }
  o.validate();
  return o;
}

int run(const IdentifyArgs& a) {
  io::OutputFolder folder(a.out, "identify");
  const io::RigReadOptions ro = frame_reduction_options("identify", a.quiet);
  rig::RigModel model = io::resolve_rig(io::read_rig_spec(a.rig), ro);
  // The effects files (as compare and diagnose take them, e.g. the ones
  // diagnose wrote) extend the model the identification inverts: a frame's
  // compliance, the rods' stiffness, a rod length or joint position error,
  // a known encoder offset or load-cell gain.
  for (const auto& f : a.effects) io::add_effects(model, f, ro);
  for (const auto& dir : a.reduced) use_reduced(model, dir);
  if (a.mass > 0) model.body.mass = a.mass;
  const identify::IdentificationOptions options = options_from(a);

  std::vector<std::filesystem::path> paths(a.data.begin(), a.data.end());
  const io::MeasurementSets data = io::read_measurement_sets(paths, model.geometry.rod_count());
  if (!a.quiet) std::fprintf(stderr, "identify: %zu set(s) read\n", data.sets.size());
  for (const auto& set : data.sets) print_record_warnings(set.records);

  report::IdentificationReport report;
  report.rig = model.name;
  report.set_names = data.names;
  for (const auto& s : data.sets) {
    std::vector<std::string> files;
    for (const auto& f : s.files) files.push_back(f.string());
    report.set_files.push_back(files);
  }
  if (!a.tare.empty()) report.tare = io::read_mass_record(a.tare);
  if (!a.reference.empty()) report.reference = io::read_mass_record(a.reference);
  if (a.static_cog.size() == 3) report.static_cog_height = a.static_cog[2];
  report.options = options;

  if (a.algorithm != "rigid" && !a.quiet &&
      !identify::identification_rig(model, identify::IdentificationAlgorithm::flexible).flexible()) {
    std::fprintf(
        stderr,
        "identify: warning: the rig model has no flexible frame or rod (no fixed_frame_flexibility, "
        "carrying_frame_flexibility, rod_compliance in the rig or --effects files, nor --reduced): the flexible "
        "algorithm equals the rigid one\n");
  }
  report::IdentifySetsOptions io_options;
  io_options.algorithm = a.algorithm;
  io_options.threads = a.threads;
  if (!a.quiet) {
    io_options.progress = [](identify::IdentificationAlgorithm alg, int done, int n) {
      std::fprintf(stderr, "identify (%s): set %d/%d done\n", identify::to_string(alg), done, n);
    };
  }
  std::vector<std::vector<const rig::Record*>> sets;
  for (const auto& set : data.sets) {
    sets.emplace_back();
    for (const auto& r : set.records) sets.back().push_back(&r);
  }
  try {
    report::identify_sets(model, sets, io_options, report);
  } catch (const report::SetError& e) {
    // An unusable record is named by its file and line; an unobservable set
    // by its folder, loose files by the first of them.
    const size_t k = e.set();
    if (e.record()) throw io::record_input_error(data.sets[k].records, *e.record());
    const std::string where = data.names[k] == "files"
                                  ? data.sets[k].files.front().string() + " (and the other files of the set)"
                                  : data.names[k];
    throw io::InputError(where, 0, "", e.what());
  }
  std::fputs(report.table().c_str(), stdout);
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  io::FileBatch batch;
  batch.add_text(out / "identification.json", report.json().dump(2) + "\n");
  batch.add_text(out / "identification.html", report::identification_html(report).html());
  folder.commit(batch);
  std::printf("wrote %s/identification.json and %s/identification.html\n", a.out.c_str(), a.out.c_str());
  return 0;
}

}  // namespace

void add_identify_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("identify", "Identify mass properties from measured free swings");
  auto a = std::make_shared<IdentifyArgs>();
  cmd->add_option("rig", a->rig, "rig YAML file")->required();
  cmd->add_option("data", a->data, "measurement files or set folders (a folder of set folders: one set each)")
      ->required();
  cmd->add_option("--algorithm", a->algorithm, "rigid, flexible or both")
      ->check(CLI::IsMember({"rigid", "flexible", "both"}));
  cmd->add_option("--effects", a->effects,
                  "YAML file with an `effects:` block added to the model first (as compare's; repeatable)");
  cmd->add_option("--reduced", a->reduced, "folder written by `rigflex reduce` (fixed or carrying frame)");
  cmd->add_option("--static-cog", a->static_cog, "CoG from the static procedure: X,Y (in plane) or X,Y,Z [m]")
      ->delimiter(',')
      ->expected(2, 3);
  cmd->add_option("--tare", a->tare, "mass properties record of the carrying frame alone (subtracted)");
  cmd->add_option("--reference", a->reference, "reference mass properties record (errors, accuracy shares)");
  cmd->add_option("--mass", a->mass, "mass from static weighing [kg] (default: the rig file's body)")->check(positive());
  cmd->add_option("--window", a->window, "Savitzky-Golay window [s]")->check(positive());
  cmd->add_option("--degree", a->degree, "Savitzky-Golay polynomial degree")->check(positive());
  cmd->add_option("--threads", a->threads, "sets identified in parallel (0: all cores)")->check(thread_count());
  cmd->add_option("--out", a->out, "output folder for identification.json")->required();
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
