#include "tool/traffic_report.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace softstep::tool {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// GB/s from bytes in ms.
double rate_gbps(double bytes, double ms) { return ms > 0.0 ? bytes / (ms * 1e6) : kNaN; }

// The share of the memory bound: the time the bytes need at the bandwidth over the time taken.
double bound_fraction(double bytes, double ms, double bandwidth_gbps) {
  return bandwidth_gbps > 0.0 ? rate_gbps(bytes, ms) / bandwidth_gbps : kNaN;
}

}  // namespace

void print_traffic(const StepTraffic& traffic, const StageTimes& stage_ms, double step_ms,
                   double bandwidth_gbps) {
  std::printf("\nmemory (a model: softstep/step_traffic.hpp; bytes a stage must read and write "
              "at least)\n");
  std::printf("  %-22s %10s %14s %8s %s\n", "stage", "MB/step", "bytes per", "GB/s",
              bandwidth_gbps > 0.0 ? "of bound" : "");
  for (int st = 0; st < kStageCount; ++st) {
    const auto i = static_cast<std::size_t>(st);
    if (traffic.bytes[i] <= 0.0 || stage_ms[i] <= 0.0) continue;
    const double per = traffic.units[i] > 0.0 ? traffic.bytes[i] / traffic.units[i] : kNaN;
    std::printf("  %-22s %10.2f %8.1f %-5s %8.1f", stage_name(static_cast<Stage>(st)),
                traffic.bytes[i] * 1e-6, per, traffic.per_row[i] ? "row" : "body",
                rate_gbps(traffic.bytes[i], stage_ms[i]));
    if (bandwidth_gbps > 0.0)
      std::printf(" %7.0f %%", 100.0 * bound_fraction(traffic.bytes[i], stage_ms[i], bandwidth_gbps));
    std::printf("\n");
  }
  std::printf("  %-22s %10.2f %14s %8.1f", "step", traffic.total() * 1e-6, "",
              rate_gbps(traffic.total(), step_ms));
  if (bandwidth_gbps > 0.0) {
    std::printf(" %7.0f %%  (of %.1f GB/s: the bound is %.3f ms)",
                100.0 * bound_fraction(traffic.total(), step_ms, bandwidth_gbps), bandwidth_gbps,
                traffic.total() / (bandwidth_gbps * 1e6));
  }
  std::printf("\n");
}

nlohmann::json traffic_json(const StepTraffic& traffic, const StageTimes& stage_ms,
                            double step_ms, double bandwidth_gbps) {
  nlohmann::json stages = nlohmann::json::object();
  for (int st = 0; st < kStageCount; ++st) {
    const auto i = static_cast<std::size_t>(st);
    if (traffic.bytes[i] <= 0.0) continue;
    stages[stage_name(static_cast<Stage>(st))] = {
        {"bytes", traffic.bytes[i]},
        {traffic.per_row[i] ? "bytes_per_row" : "bytes_per_body",
         traffic.bytes[i] / traffic.units[i]},
        {"gb_per_s", rate_gbps(traffic.bytes[i], stage_ms[i])}};
  }
  nlohmann::json j = {{"model_bytes_per_step", traffic.total()},
                      {"gb_per_s", rate_gbps(traffic.total(), step_ms)},
                      {"stages", stages}};
  if (bandwidth_gbps > 0.0) {
    j["bandwidth_gb_per_s"] = bandwidth_gbps;
    j["bound_fraction"] = bound_fraction(traffic.total(), step_ms, bandwidth_gbps);
  }
  return j;
}

}  // namespace softstep::tool
