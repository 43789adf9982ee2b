#pragma once

#include "tool/arguments.hpp"

namespace softstep::tool {

// softstep hardcases [--simd W] [--quick]: runs the hard-case suite and prints its table.
int hardcases_command(Arguments& args);
extern const char* const kHardcasesUsage;

}  // namespace softstep::tool
