// Milliseconds between two steady_clock readings, as the step's profile reports its times.
#pragma once

#include <chrono>

namespace softstep {

inline double ms_between(std::chrono::steady_clock::time_point from,
                         std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

inline double ms_since(std::chrono::steady_clock::time_point from) {
  return ms_between(from, std::chrono::steady_clock::now());
}

}  // namespace softstep
