#pragma once
// What every bench/ program's command line and timings need.
#include <chrono>
#include <stdexcept>
#include <string>

namespace rigflex::bench {

using clock_type = std::chrono::steady_clock;

inline double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

// The value after option argv[i] (advancing i past it); throws when missing.
inline std::string option_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
  return argv[++i];
}

}  // namespace rigflex::bench
