#pragma once
// The subcommands of the rigflex command line; each returns the exit code.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>

namespace rigflex::app {

void add_mass_command(CLI::App& app, int& exit_code);
void add_modes_command(CLI::App& app, int& exit_code);
void add_reduce_command(CLI::App& app, int& exit_code);
void add_simulate_command(CLI::App& app, int& exit_code);
void add_check_command(CLI::App& app, int& exit_code);
void add_identify_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
void add_compare_command(CLI::App& app, int& exit_code);
void add_diagnose_command(CLI::App& app, int& exit_code);

// A value > 0, refused with a plain message ("--histories: must be positive,
// got 0"): CLI11's PositiveNumber names its range up to 1.8e308.
inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0') return "expected a number, got '" + s + "'";
        return v > 0 ? std::string() : "must be positive, got " + s;
      },
      "> 0");
}

}  // namespace rigflex::app
