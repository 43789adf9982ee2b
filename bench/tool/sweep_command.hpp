#pragma once

#include <string>

#include "tool/arguments.hpp"

namespace softstep::tool {

// softstep sweep [scene] --out DIR ...: what accuracy costs in time, over a grid of settings.
int sweep_command(Arguments& args);
extern const std::string kSweepUsage;

}  // namespace softstep::tool
