// Threads of one run: the flow's per-cell and per-face stages split over threads (OpenMP), with results
// bit for bit identical for any thread count (docs/threads.md).
//
// Determinism rule: a parallel loop splits rows, columns or lines whose values are each computed by the
// same operations as in one thread, and no two threads write the same value. A sum over many values
// (the pressure solver's dot products, a water budget) keeps its one fixed order and runs on one
// thread; a largest value is taken row by row and the rows' largest in row order (the first of equal
// ones), which is what one thread does. Hence a run's state does not depend on the thread count.
//
// The count is one setting of the process (as OpenMP's own), read by every solver's next parallel loop.
// Without OpenMP at build time every loop runs on the calling thread and set_threads accepts 1 only.
#pragma once

namespace vofdem {

// the most threads set_threads accepts: 256 with OpenMP (more than the cores is allowed, and slower),
// 1 without
int max_threads();

// threads of the next parallel loops [-], in [1, max_threads()]; default: OMP_NUM_THREADS when set,
// else every core. std::invalid_argument naming the parameter and the allowed range otherwise
void set_threads(int n);
int threads();

// the fewest cells (or faces, or line elements) a thread is given [-], in [1, 1e9], default 2048: a
// loop over fewer per thread runs on fewer threads (a thread's share below about 10 microseconds of
// work costs more to hand out than it saves). 1 splits every loop, which the determinism tests use
void set_thread_min_cells(int n);
int thread_min_cells();

// true if the library was built with OpenMP
bool built_with_openmp();

}  // namespace vofdem
