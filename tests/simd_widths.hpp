// Every lane width the library has, for the tests that compare them bit for bit, and whether
// this CPU runs one: a width it lacks is skipped, and the test's output says so.
#pragma once

#include <iostream>
#include <set>

#include "softstep/world.hpp"

namespace softstep::test {

inline constexpr SimdWidth kEveryWidth[] = {SimdWidth::Scalar, SimdWidth::Sse, SimdWidth::Avx2,
                                            SimdWidth::Avx512};

// World refuses a width this CPU lacks (naming what it lacks); that refusal is the one test
// of support a user has too. Prints a "[ NO WIDTH ]" line once per missing width.
inline bool cpu_runs(SimdWidth width) {
  try {
    WorldSettings s;
    s.simd = width;
    World world(s);
    return true;
  } catch (const InvalidArgument& e) {
    static std::set<SimdWidth> reported;
    if (reported.insert(width).second) {
      // Not gtest's "[  SKIPPED ]": ctest marks a test whose output has that as skipped even
      // when it failed, and the widths this CPU runs were still compared.
      std::cout << "[ NO WIDTH ] " << simd_width_name(width) << ": " << e.what() << "\n";
    }
    return false;
  }
}

}  // namespace softstep::test
