#include "diagnose/fftw_planner.hpp"

namespace rigflex::diagnose {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace rigflex::diagnose
