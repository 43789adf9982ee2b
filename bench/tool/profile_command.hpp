#pragma once

#include <string>

#include "tool/arguments.hpp"

namespace softstep::tool {

// softstep profile [chain] --links N --chains M ... : runs a scene and reports its cost.
int profile_command(Arguments& args);
extern const std::string kProfileUsage;

}  // namespace softstep::tool
