#include "vofdem/common/profile.h"

#include <numeric>

namespace vofdem {

int StageProfile::add_stage(const std::string& name) {
  const int existing = find(name);
  if (existing >= 0) return existing;
  names_.push_back(name);
  seconds_.push_back(0.0);
  calls_.push_back(0);
  return static_cast<int>(names_.size()) - 1;
}

int StageProfile::find(const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return static_cast<int>(i);
  return -1;
}

void StageProfile::reset() {
  std::fill(seconds_.begin(), seconds_.end(), 0.0);
  std::fill(calls_.begin(), calls_.end(), 0LL);
}

double StageProfile::total_seconds() const { return std::accumulate(seconds_.begin(), seconds_.end(), 0.0); }

}  // namespace vofdem
