// The weir packing generators' random draws (weir_packing.cpp, weir_packing_3d.cpp): the same numbers
// from a seed with any standard library, so that a seed gives the same weir bit for bit.
#pragma once

#include <random>

#include "vofdem/stones/weir_packing.h"

namespace vofdem::packing_random {

// uniform in [0, 1) from the top 53 bits, independent of the standard library's distributions
inline double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

// a stone's nominal diameter d_mean (1 + d_spread (2u - 1)) [m]
inline double diameter(std::mt19937_64& g, const WeirSpec& s) {
  return s.d_mean * (1.0 + s.d_spread * (2.0 * uniform01(g) - 1.0));
}

}  // namespace vofdem::packing_random
