#pragma once
// What every bench/ program's command line and timings need.
#include <chrono>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

// The items of a comma-separated option value ("a,b,c").
inline std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

}  // namespace rigflex::bench
