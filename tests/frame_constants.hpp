// The constants most tests share: one frame at 60 Hz, gravity, pi. Defined once, so that the
// test files also compile together (the test program is a unity build: see CMakeLists.txt).
#pragma once

#include <numbers>

namespace softstep::test {

inline constexpr double kDt = 1.0 / 60.0;  // s: one frame at 60 Hz
inline constexpr double kG = 9.81;         // m/s^2
inline constexpr double kPi = std::numbers::pi;

}  // namespace softstep::test
