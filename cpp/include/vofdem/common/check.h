// Argument checks shared by every module.
//
// Bad input is refused with std::invalid_argument (Python sees ValueError) whose message names the
// parameter, the value given and the allowed range, so a user can fix the call without reading code.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace vofdem {

// formats a double the way the error messages show it (shortest round-trip form)
std::string format_value(double value);

// value must be finite
void require_finite(const char* name, double value);
// value must be finite and > 0
void require_positive(const char* name, double value);
// value must be finite and >= 0
void require_non_negative(const char* name, double value);
// value must lie in (lo, hi] (open below, closed above), e.g. a porosity in (0, 1]
void require_in_open_closed(const char* name, double value, double lo, double hi);
// value must lie in [lo, hi]
void require_in_closed(const char* name, double value, double lo, double hi);

// an array of a state (a copy or a checkpoint) must hold `size` values
template <class T>
void require_size(const char* name, const std::vector<T>& v, std::size_t size) {
  if (v.size() != size)
    throw std::invalid_argument(std::string("state: '") + name + "' has " + std::to_string(v.size()) +
                                " values, expected " + std::to_string(size));
}

// A step whose velocities carry a cell's content further than one cell (Courant number > 1). The
// velocities a step creates (a stone moving into a pore, a jet leaving the crest) are not known when its
// length is chosen, so a caller that chooses the step may take it again, shorter.
class CflBreach : public std::runtime_error {
 public:
  CflBreach(const std::string& what, double courant) : std::runtime_error(what), courant_(courant) {}
  double courant() const { return courant_; }  // the Courant number reached [-]

 private:
  double courant_;
};

}  // namespace vofdem
