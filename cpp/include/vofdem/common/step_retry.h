// A step taken again, shorter, when the velocities it created breach the CFL condition.
//
// A step's length comes from the velocities at its start; the velocities it creates (a stone moving into
// a pore, a jet leaving the crest) can cross more than one cell within it. The step then throws CflBreach
// after restoring its start, and is retried with dt * min(1/2, cfl / Courant), which brings the breach
// back to the target Courant number if the new velocities stay what they were (the adaptive step
// rejection of explicit free-surface solvers). A step that needs no retry is untouched, so runs that
// never breach are bit for bit those without this loop.
#pragma once

#include <algorithm>
#include <string>

#include "vofdem/common/check.h"

namespace vofdem {

constexpr int kMaxStepRetries = 4;  // at least 16 times shorter before giving up

// calls step(dt) until it does not throw CflBreach (at most kMaxStepRetries retries, none below
// min_dt [s]); on_retry(dt) is called before each retry with its shorter dt; returns the dt taken
template <class Step, class OnRetry>
double step_with_retries(double dt, double cfl, double min_dt, Step&& step, OnRetry&& on_retry) {
  for (int retry = 0;; ++retry) {
    try {
      step(dt);
      return dt;
    } catch (const CflBreach& e) {
      const double shorter = dt * std::min(0.5, cfl / e.courant());
      if (retry == kMaxStepRetries || shorter < min_dt)
        throw CflBreach(std::string(e.what()) + " (after " + std::to_string(retry) +
                            " retries with shorter steps, the last dt = " + format_value(dt) + " s)",
                        e.courant());
      dt = shorter;
      on_retry(dt);
    }
  }
}

}  // namespace vofdem
