#pragma once
// FFTW's planner (plan creation and destruction) is not thread-safe, and
// diagnose plans in parallel loops: every plan of this library is made and
// destroyed under this one lock. fftw_execute on distinct arrays is safe.
#include <mutex>

namespace rigflex::diagnose {

std::mutex& fftw_planner_mutex();

}  // namespace rigflex::diagnose
