// `softstep profile`'s memory section: the bytes each stage must move (the model in
// softstep/step_traffic.hpp), the rate the measured stage times give, and with --bandwidth
// the fraction of the memory bound reached.
#pragma once

#include <nlohmann/json.hpp>

#include "tool/report_files.hpp"
#include "softstep/step_traffic.hpp"

namespace softstep::tool {

// bandwidth_gbps: a triad bandwidth (softstep_bandwidth_bench), 0 when not given.
void print_traffic(const StepTraffic& traffic, const StageTimes& stage_ms, double step_ms,
                   double bandwidth_gbps);
nlohmann::json traffic_json(const StepTraffic& traffic, const StageTimes& stage_ms,
                            double step_ms, double bandwidth_gbps);

}  // namespace softstep::tool
