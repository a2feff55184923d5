// Internal: the library's parallel loops (vofdem/common/threads.h for the rule that keeps them
// deterministic). parallel_for hands each thread one contiguous piece of [0, n); which thread computes
// an item never changes its value, so the pieces may follow the thread count. Bodies must not throw
// (an exception cannot leave an OpenMP region): check before the loop, or flag and throw after it.
#pragma once

#include <algorithm>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/common/threads.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace vofdem::detail {

// threads for n items of `work` cells each: at most threads(), one per item and one per
// thread_min_cells() cells of the whole loop
inline int loop_threads(long long n, long long work) {
  const int t = threads();
  if (t <= 1 || n <= 1) return 1;
  const long long by_work = n * std::max(work, 1LL) / thread_min_cells();
  return static_cast<int>(std::max(1LL, std::min({static_cast<long long>(t), n, by_work})));
}

// body(id, count) on `count` threads at once (count <= 1: on the calling thread with (0, 1)); a body
// may wait on another thread of the team (they all run). Each thread calls its own copy of the body:
// the values it captured by copy stay in registers (a value the loops read through a reference to the
// caller's variable, whose address the team shares, is read again after every store to a double, and
// such loops do not vectorise); so a body captures the doubles its loops read by value
template <class Body>
void parallel_team(int count, const Body& body) {
#ifdef _OPENMP
  if (count > 1) {
#pragma omp parallel num_threads(count)
    {
      Body local = body;
      local(omp_get_thread_num(), omp_get_num_threads());
    }
    return;
  }
#else
  (void)count;  // one thread without OpenMP
#endif
  Body local = body;
  local(0, 1);
}

// inside parallel_team's body: waits until every thread of the team has arrived here (each thread must
// pass the same barriers in the same order)
inline void team_barrier() {
#ifdef _OPENMP
#pragma omp barrier
#endif
}

// the piece [begin, end) of thread `id` of `count` over n items (contiguous, in order, sizes within one)
inline void piece(int n, int id, int count, int& begin, int& end) {
  begin = static_cast<int>(static_cast<long long>(n) * id / count);
  end = static_cast<int>(static_cast<long long>(n) * (id + 1) / count);
}

// body(begin, end) over contiguous pieces of [0, n), each item `work` cells (rows of nx: work = nx)
template <class Body>
void parallel_for(int n, long long work, const Body& body) {
  if (n <= 0) return;
  parallel_team(loop_threads(n, work), [&body, n](int id, int count) {
    int b, e;
    piece(n, id, count, b, e);
    if (b >= e) return;
    Body local = body;
    local(b, e);
  });
}

// body(begin, end) over pieces of [0, n) for a loop over single values (a vector's update): the pieces
// are whole blocks of 1024 values
template <class Body>
void parallel_range(long long n, const Body& body) {
  constexpr long long kBlock = 1024;
  const int blocks = static_cast<int>((n + kBlock - 1) / kBlock);
  parallel_for(blocks, kBlock, [&body, n](int b0, int b1) {
    Body local = body;
    local(b0 * kBlock, std::min(n, b1 * kBlock));
  });
}

// The largest value of each row and its first position (take_row_maximum of grid.h on each row), the
// rows on the threads. work holds row_maxima_size(rows, width) values: after the call work[k] is row k's
// largest value (0 if none is positive) and work[rows + k] its first position. fill(k, buffer) writes row
// k's values at the start of a buffer of `width` values (one per thread, after the results; the rest is
// the fill's own work space) and returns their count. The caller then takes the rows in order, as one
// thread would: a row whose largest beats the largest so far gives the new position
inline std::size_t row_maxima_size(int rows, int width) {
  return 2 * static_cast<std::size_t>(rows) + static_cast<std::size_t>(loop_threads(rows, width)) * width;
}

template <class Fill>
void row_maxima(int rows, int width, double* work, const Fill& fill) {
  parallel_team(loop_threads(rows, width), [&](int id, int team) {
    int k0, k1;
    piece(rows, id, team, k0, k1);
    double* row = work + 2 * static_cast<std::size_t>(rows) + static_cast<std::size_t>(id) * width;
    Fill local = fill;
    for (int k = k0; k < k1; ++k) {
      const int n = local(k, row);
      double worst = 0.0;
      int first = -1;
      if (n > 0) take_row_maximum(row, n, worst, first);
      work[k] = worst;
      work[rows + k] = first;
    }
  });
}

}  // namespace vofdem::detail
