// The step plan as `softstep profile --plan` prints it and as its --json report holds it.
#pragma once

#include <nlohmann/json.hpp>

#include "softstep/step_plan.hpp"

namespace softstep::tool {

void print_plan(const StepPlan& plan);
nlohmann::json plan_json(const StepPlan& plan);

}  // namespace softstep::tool
