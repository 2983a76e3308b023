#pragma once
// Running the rigflex binary from the CLI tests.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace rigflex::test {

namespace fs = std::filesystem;

struct CliRun {
  int code = 0;
  std::string out;
};

// Runs a shell command line; its exit code and its output (both streams if
// the line says 2>&1).
inline CliRun run_command(const std::string& cmd) {
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, "popen could not start: " + cmd};
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline CliRun run(const std::string& args) { return run_command(std::string(RIGFLEX_CLI) + " " + args + " 2>&1"); }

inline nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

inline fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("rigflex_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

inline std::string example(const std::string& name) { return std::string(RIGFLEX_SOURCE_DIR) + "/examples/" + name + "/model.yaml"; }

inline fs::path write_model(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(p) << text;
  return p;
}

}  // namespace rigflex::test
