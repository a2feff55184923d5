// Argument checks shared by every module.
//
// Bad input is refused with std::invalid_argument (Python sees ValueError) whose message names the
// parameter, the value given and the allowed range, so a user can fix the call without reading code.
#pragma once

#include <string>

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

}  // namespace vofdem
