// A coupler stage timed twice: Coupler::profile() the wall clock, Coupler::cpu_profile() the process's CPU
// time. On a machine shared with other work a stage's wall time counts its waits for a core, its CPU time
// does not. The CPU clock is a system call (0.57 us a reading more than the wall clock's on a 2-core Linux
// VM; 12 readings a coupled step, 0.52 % of a step on the paper's grid: benchmarks/results/
// stage_timer_clock.md), so the flow's and the stones' own timers, hundreds of stages a step, keep the
// wall clock alone.
#pragma once

#include <time.h>

#include "vofdem/common/profile.h"

namespace vofdem {

// the process's CPU time [s]: all of its threads, the OpenMP team's included
inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// times the enclosing scope into one stage of both profiles (the same index in each)
class CoupledStage {
 public:
  CoupledStage(StageProfile& wall, StageProfile& cpu, int stage)
      : wall_(wall, stage), cpu_(cpu), stage_(stage), start_(process_cpu_seconds()) {}
  ~CoupledStage() { cpu_.add(stage_, process_cpu_seconds() - start_); }
  CoupledStage(const CoupledStage&) = delete;
  CoupledStage& operator=(const CoupledStage&) = delete;

 private:
  ScopedStage wall_;
  StageProfile& cpu_;
  int stage_;
  double start_;
};

}  // namespace vofdem
