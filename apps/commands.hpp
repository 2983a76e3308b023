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
void add_export_command(CLI::App& app, int& exit_code);

// A number accepted when `ok(value)`, else refused with a plain message
// ("--histories: must be positive, got 0"): CLI11's PositiveNumber names its
// range up to 1.8e308. `whole`: an integer is expected.
template <class Ok>
CLI::Validator number_check(Ok ok, bool whole, std::string refusal, std::string label) {
  return CLI::Validator(
      [ok, whole, refusal](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = whole ? static_cast<double>(std::strtol(s.c_str(), &end, 10)) : std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0')
          return (whole ? "expected a whole number, got '" : "expected a number, got '") + s + "'";
        return ok(v) ? std::string() : refusal + ", got " + s;
      },
      std::move(label));
}

inline CLI::Validator positive() {
  return number_check([](double v) { return v > 0; }, false, "must be positive", "> 0");
}
inline CLI::Validator non_negative() {
  return number_check([](double v) { return v >= 0; }, false, "must not be negative", ">= 0");
}
// A thread count: 0 (all cores) to 1024.
inline CLI::Validator thread_count() {
  return number_check([](double v) { return v >= 0 && v <= 1024; }, true, "expected 0 (all cores) to 1024", "0-1024");
}

}  // namespace rigflex::app
