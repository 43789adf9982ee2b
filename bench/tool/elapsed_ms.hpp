// Milliseconds since a steady_clock reading, as the tool reports what it times around the
// library (collision, readings, recording, sweeps). The library's own: core/src/elapsed_ms.hpp.
#pragma once

#include <chrono>

namespace softstep::tool {

inline double ms_between(std::chrono::steady_clock::time_point from,
                         std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

inline double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return ms_between(since, std::chrono::steady_clock::now());
}

}  // namespace softstep::tool
