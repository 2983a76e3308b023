#pragma once
// Wall time of a solver phase, for the statistics the solvers report.
#include <chrono>

namespace rigflex::linalg {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rigflex::linalg
