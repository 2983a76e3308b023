#pragma once
// The subcommands of the rigflex command line; each returns the exit code.
#include <CLI/CLI.hpp>

namespace rigflex::app {

void add_mass_command(CLI::App& app, int& exit_code);
void add_modes_command(CLI::App& app, int& exit_code);
void add_reduce_command(CLI::App& app, int& exit_code);
void add_simulate_command(CLI::App& app, int& exit_code);
void add_check_command(CLI::App& app, int& exit_code);

}  // namespace rigflex::app
