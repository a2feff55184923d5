#include "vofdem/common/check.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace vofdem {

std::string format_value(double value) {
  // the shortest of 15..17 significant digits that reads back as the same double
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    if (std::strtod(buf, nullptr) == value || std::isnan(value)) break;
  }
  return buf;
}

namespace {
[[noreturn]] void refuse(const char* name, double value, const std::string& range) {
  throw std::invalid_argument(std::string(name) + " = " + format_value(value) + " is outside the allowed range " +
                              range);
}
}  // namespace

void require_finite(const char* name, double value) {
  if (!std::isfinite(value)) refuse(name, value, "(finite values)");
}

void require_positive(const char* name, double value) {
  if (!(std::isfinite(value) && value > 0.0)) refuse(name, value, "(0, inf)");
}

void require_non_negative(const char* name, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) refuse(name, value, "[0, inf)");
}

void require_in_open_closed(const char* name, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value > lo && value <= hi))
    refuse(name, value, "(" + format_value(lo) + ", " + format_value(hi) + "]");
}

void require_in_closed(const char* name, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi))
    refuse(name, value, "[" + format_value(lo) + ", " + format_value(hi) + "]");
}

}  // namespace vofdem
