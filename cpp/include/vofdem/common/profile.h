// Per-stage wall-clock profile of a solver step, in the manner of Box2D's b2Profile.
//
// Each solver owns one StageProfile; every stage of its step is wrapped in a ScopedStage so that the
// user can read where the time goes. A stage whose effect is switched off is never entered, so it
// costs nothing and its count stays zero.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace vofdem {

class StageProfile {
 public:
  // registers a stage and returns its index; call at construction, not while stepping
  int add_stage(const std::string& name);
  // index of a registered stage, or -1
  int find(const std::string& name) const;

  void add(int stage, double seconds) {
    seconds_[stage] += seconds;
    calls_[stage] += 1;
  }
  void reset();

  const std::vector<std::string>& names() const { return names_; }
  // accumulated wall time of each stage [s]
  const std::vector<double>& seconds() const { return seconds_; }
  // number of times each stage ran
  const std::vector<long long>& calls() const { return calls_; }
  double total_seconds() const;

 private:
  std::vector<std::string> names_;
  std::vector<double> seconds_;
  std::vector<long long> calls_;
};

// times the enclosing scope into one stage of a profile
class ScopedStage {
 public:
  ScopedStage(StageProfile& profile, int stage)
      : profile_(profile), stage_(stage), start_(std::chrono::steady_clock::now()) {}
  ~ScopedStage() {
    const auto end = std::chrono::steady_clock::now();
    profile_.add(stage_, std::chrono::duration<double>(end - start_).count());
  }
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

 private:
  StageProfile& profile_;
  int stage_;
  std::chrono::steady_clock::time_point start_;
};

// times a run of consecutive stages with one clock reading per stage (a loop of short stages, as the
// DEM's substeps, reads the clock once per stage instead of twice): the time since the last lap (or
// the start) goes to the stage named by the next lap
class StageLaps {
 public:
  explicit StageLaps(StageProfile& profile) : profile_(profile), last_(std::chrono::steady_clock::now()) {}
  void lap(int stage) {
    const auto now = std::chrono::steady_clock::now();
    profile_.add(stage, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }
  StageLaps(const StageLaps&) = delete;
  StageLaps& operator=(const StageLaps&) = delete;

 private:
  StageProfile& profile_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace vofdem
