// rigflex: flexible models, modes and reduction of multi-filar pendulum rigs.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "apps/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

int main(int argc, char** argv) {
  // Ctrl-C or a kill while results are written leaves no *.tmp-rigflex-* behind.
  rigflex::io::remove_temporaries_on_signals();
  CLI::App app{"rigflex: frame models, modes, reduction, rig simulation and design check for multi-filar pendulum rigs"};
  app.set_version_flag("--version", std::string("rigflex ") + RIGFLEX_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  rigflex::app::add_mass_command(app, exit_code);
  rigflex::app::add_export_command(app, exit_code);
  rigflex::app::add_modes_command(app, exit_code);
  rigflex::app::add_reduce_command(app, exit_code);
  rigflex::app::add_simulate_command(app, exit_code);
  rigflex::app::add_check_command(app, exit_code);
  rigflex::app::add_identify_command(app, exit_code);
  rigflex::app::add_sweep_command(app, exit_code);
  rigflex::app::add_compare_command(app, exit_code);
  rigflex::app::add_diagnose_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end parsing with code 0; every usage error is a
    // bad input, exit 2 as documented (CLI11's own codes are 100-115).
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const rigflex::io::InputError& e) {
    std::cerr << "rigflex: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "rigflex: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rigflex: failed: " << e.what() << "\n";
    return 3;
  }
  return exit_code;
}
