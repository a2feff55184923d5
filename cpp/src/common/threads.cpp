#include "vofdem/common/threads.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#include <pthread.h>
#endif

namespace vofdem {

namespace {

constexpr int kMaxThreads = 256;
constexpr int kMaxMinCells = 1000000000;

// OMP_NUM_THREADS when set, else the cores (OpenMP's own default), within the allowed range
int default_threads() {
#ifdef _OPENMP
  return std::clamp(omp_get_max_threads(), 1, kMaxThreads);
#else
  return 1;
#endif
}

std::atomic<int>& thread_count() {
  static std::atomic<int> n{default_threads()};
  return n;
}

#ifdef _OPENMP
// A process forked after a parallel loop holds none of the parent's OpenMP threads, and GNU OpenMP hangs
// in its next parallel region: a forked child runs its loops on one thread (set_threads again at its
// own risk; a child that execs, or a process started by spawn, has its own default)
const bool one_thread_after_fork = [] {
  pthread_atfork(nullptr, nullptr, [] { thread_count().store(1, std::memory_order_relaxed); });
  return true;
}();
#endif

std::atomic<int> min_cells{2048};

}  // namespace

int max_threads() {
#ifdef _OPENMP
  return kMaxThreads;
#else
  return 1;
#endif
}

void set_threads(int n) {
  if (n < 1 || n > max_threads())
    throw std::invalid_argument("threads = " + std::to_string(n) + " is outside the allowed range [1, " +
                                std::to_string(max_threads()) + "]" +
                                (built_with_openmp() ? "" : " (built without OpenMP)"));
  thread_count().store(n, std::memory_order_relaxed);
}

int threads() { return thread_count().load(std::memory_order_relaxed); }

void set_thread_min_cells(int n) {
  if (n < 1 || n > kMaxMinCells)
    throw std::invalid_argument("thread_min_cells = " + std::to_string(n) + " is outside the allowed range [1, " +
                                std::to_string(kMaxMinCells) + "]");
  min_cells.store(n, std::memory_order_relaxed);
}

int thread_min_cells() { return min_cells.load(std::memory_order_relaxed); }

bool built_with_openmp() {
#ifdef _OPENMP
  return true;
#else
  return false;
#endif
}

}  // namespace vofdem
