// rigflex export: a model as a CalculiX / Abaqus deck, a reduced frame as
// Nastran DMIG cards or Abaqus matrices (docs/model-exchange.md).
#include <cstdio>
#include <filesystem>

#include "apps/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/calculix_deck.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_export.hpp"
#include "io/reduced_solver_formats.hpp"

namespace rigflex::app {
namespace {
namespace fs = std::filesystem;

struct ExportArgs {
  std::string model;
  std::string reduced;
  std::string deck, dmig, abaqus_matrix;
  std::string dialect = "calculix";
  int modes = 10;
};

int run(const ExportArgs& a) {
  if (a.model.empty() == a.reduced.empty())
    throw std::invalid_argument("export: give a model file or --reduced DIR (one of them)");
  if (!a.model.empty()) {
    if (a.deck.empty() || !a.dmig.empty() || !a.abaqus_matrix.empty())
      throw std::invalid_argument("export MODEL: --deck FILE.inp is what a model exports to");
    const io::ModelFile m = io::read_model(a.model);
    io::CalculixOptions o;
    o.dialect = a.dialect == "abaqus" ? io::CalculixDialect::abaqus : io::CalculixDialect::calculix;
    o.modes = a.modes;
    o.heading = m.name;
    io::write_text_atomically(a.deck, io::calculix_input(m.model, o));
    std::printf("wrote %s (%s deck, *FREQUENCY %d modes)\n", a.deck.c_str(), a.dialect.c_str(), a.modes);
    return 0;
  }
  if (!a.deck.empty() || (a.dmig.empty() && a.abaqus_matrix.empty()))
    throw std::invalid_argument("export --reduced: give --dmig FILE and/or --abaqus-matrix FILE.inp");
  const reduction::ReducedFrame r = io::read_reduced_frame(a.reduced);
  if (!a.dmig.empty()) {
    io::write_text_atomically(a.dmig, io::nastran_dmig(r));
    std::printf("wrote %s (KAAX, MAAX, BAAX)\n", a.dmig.c_str());
  }
  if (!a.abaqus_matrix.empty()) {
    const fs::path target(a.abaqus_matrix);
    if (target.extension() != ".inp") throw std::invalid_argument("--abaqus-matrix: a file name ending in .inp");
    io::FileBatch batch;
    for (const auto& [name, text] : io::abaqus_matrix_files(r, target.stem().string()))
      batch.add_text(target.parent_path() / name, text);
    batch.commit();
    std::printf("wrote %s and its matrix files beside it\n", a.abaqus_matrix.c_str());
  }
  return 0;
}

}  // namespace

void add_export_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("export",
                                 "Write a model as a CalculiX / Abaqus deck, or a reduced frame as Nastran "
                                 "DMIG cards or Abaqus matrices");
  auto a = std::make_shared<ExportArgs>();
  cmd->add_option("model", a->model, "model file (.yaml or .inp) to write as a deck");
  cmd->add_option("--reduced", a->reduced, "folder rigflex reduce wrote");
  cmd->add_option("--deck", a->deck, "the model's deck (.inp)");
  cmd->add_option("--for", a->dialect, "calculix | abaqus: the program that reads the deck")
      ->check(CLI::IsMember({"calculix", "abaqus"}));
  cmd->add_option("--modes", a->modes, "modes the deck's *FREQUENCY step asks for")->check(CLI::PositiveNumber);
  cmd->add_option("--dmig", a->dmig, "Nastran DMIG file of the reduced frame");
  cmd->add_option("--abaqus-matrix", a->abaqus_matrix, "Abaqus include file (.inp) of the reduced frame's matrices");
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
