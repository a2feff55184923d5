// Mathematical constants of the library, each written once (M_PI is POSIX, not C++17, and std::numbers
// arrives with C++20).
#pragma once

namespace vofdem {

inline constexpr double kPi = 3.14159265358979323846;  // pi [-]

}  // namespace vofdem
