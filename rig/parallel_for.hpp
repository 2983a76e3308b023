#pragma once
// Runs body(i) for i in [0, count) on up to `threads` threads (0: the
// hardware's), each index exactly once. After an exception the remaining
// indices are skipped; once all threads have stopped, the exception of the
// lowest index that threw is rethrown (which one does not depend on timing
// among those that ran).
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rigflex::rig {

template <class Body>
void parallel_for(int count, int threads, Body body) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, count);
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  int error_index = count;
  std::mutex error_mutex;
  auto work = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (i < error_index) error = std::current_exception(), error_index = i;
        failed = true;
      }
    }
  };
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    try {
      for (int t = 0; t < threads; ++t) pool.emplace_back(work);
    } catch (...) {
      // A thread that cannot start: the started ones finish the work (or
      // stop at the first error); none is left joinable.
      if (pool.empty()) work();
    }
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace rigflex::rig
