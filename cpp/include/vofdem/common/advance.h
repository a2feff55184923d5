// The advance loop shared by the flow (VOFGrid::advance) and the coupled solver (Coupler::advance):
// steps of the stable step until the time reaches t_end.
//
//   dt_s = stable step at the step's start;  dt_s < min_dt: the step collapsed (a failure)
//   dt   = left                 if dt_s >= left        (left = t_end - t)
//        = left / 2             if left / 2 < dt_s < left
//        = dt_s                 otherwise
//
// so the last steps split the remainder evenly rather than leaving a sliver, and a remainder below
// 1e-12 max(1, |t_end|) closes the loop (no step of round-off size). Each step is taken again, shorter,
// while it breaches the CFL (step_retry.h). The owner keeps its own bookkeeping (the growth limit's
// last step, counters of retries and binding limits) in the callbacks.
#pragma once

#include <algorithm>
#include <cmath>

#include "vofdem/common/check.h"
#include "vofdem/common/step_retry.h"

namespace vofdem {

// what the owner reports at a step's start: its stable step and the limits the step is taken under
struct AdvanceLimits {
  double stable_dt;  // [s]
  double min_dt;     // a stable step below this is a failure [s]
  double cfl;        // target Courant number of a retried step (step_with_retries)
};

// one step of the loop, handed to the owner after it was taken
struct AdvanceStep {
  double stable;  // the stable step [s]
  double dt;      // the step asked for: the stable one, or cut to split the remainder [s]
  double taken;   // the step taken: dt, or shorter after retries [s]
  int retries;    // how often it was taken again, shorter
};

// runs the loop until time() reaches t_end [s] and returns the number of steps:
//   time()            the owner's time [s]
//   limits()          AdvanceLimits at the step's start
//   collapse(dt)      throws: the stable step dt [s] is below min_dt
//   step(dt)          one step of dt [s] (throws CflBreach to be retried shorter)
//   on_retry(dt)      before each retry, with its shorter dt [s]
//   stepped(s)        after each step, with its AdvanceStep
// t_end must be finite (std::invalid_argument otherwise)
template <class Time, class Limits, class Collapse, class Step, class OnRetry, class Stepped>
long long advance_until(double t_end, Time&& time, Limits&& limits, Collapse&& collapse, Step&& step,
                        OnRetry&& on_retry, Stepped&& stepped) {
  require_finite("t_end", t_end);
  long long n = 0;
  // a step shorter than this closes the remaining interval (avoids a last step of round-off size)
  const double eps = 1e-12 * std::max(1.0, std::abs(t_end));
  while (time() < t_end - eps) {
    const AdvanceLimits lim = limits();
    const double stable = lim.stable_dt;
    if (stable < lim.min_dt) collapse(stable);
    // the last steps split the remainder evenly rather than leaving a sliver
    const double left = t_end - time();
    double dt = stable;
    if (dt >= left) dt = left;
    else if (dt > 0.5 * left) dt = 0.5 * left;
    int retries = 0;
    const double taken = step_with_retries(dt, lim.cfl, lim.min_dt, step, [&](double h) {
      ++retries;
      on_retry(h);
    });
    ++n;
    stepped(AdvanceStep{stable, dt, taken, retries});
  }
  return n;
}

}  // namespace vofdem
