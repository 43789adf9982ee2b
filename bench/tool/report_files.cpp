#include "tool/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tool/arguments.hpp"

namespace softstep::tool {

namespace {
constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();  // "null" in the CSV
}  // namespace

std::string format_number(double value) {
  if (!std::isfinite(value)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", value);
  return b;
}

void Trace::add_step(double step_start_us, const StepProfile& profile) {
  for (std::size_t t = 0; t < profile.thread_events.size(); ++t) {
    for (const StageEvent& e : profile.thread_events[t])
      events_.push_back({stage_name(e.stage), t, step_start_us + e.start_us, e.end_us - e.start_us});
  }
}

void Trace::add_slice(const char* name, std::size_t thread, double start_us, double duration_us) {
  events_.push_back({name, thread, start_us, duration_us});
}

std::string Trace::text() const {
  nlohmann::json events = nlohmann::json::array();
  for (const Event& e : events_) {
    events.push_back({{"name", e.name},
                      {"cat", "step"},
                      {"ph", "X"},
                      {"ts", e.start_us},
                      {"dur", e.duration_us},
                      {"pid", 1},
                      {"tid", e.thread}});
  }
  return nlohmann::json{{"traceEvents", events}}.dump() + "\n";
}

std::string markup_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

void check_writable_file(const std::string& flag, const std::string& path) {
  if (path.empty()) return;
  std::error_code ec;
  const bool existed = std::filesystem::exists(path, ec);
  // Append mode creates the file without truncating one that is there.
  const bool ok = std::ofstream(path, std::ios::binary | std::ios::app).good();
  if (!existed) std::filesystem::remove(path, ec);
  if (!ok) throw UsageError(flag + " " + path + ": cannot write a file there");
}

void check_writable_directory(const std::string& flag, const std::string& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory)) {
    throw UsageError(flag + " " + directory + ": cannot create the directory (" +
                     (ec ? ec.message() : std::string("a file is in the way")) + ")");
  }
  const std::string probe = (std::filesystem::path(directory) / ".softstep_write_check").string();
  check_writable_file(flag, probe);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void StepSamples::add(const StepProfile& p, double ms, double start_us) {
  step_ms.push_back(ms);
  stage_ms.push_back(p.stage_ms);
  threads.push_back(p.threads);
  if (p.threads > 1) ++shared_steps;
  double waited = 0.0;
  for (double w : p.barrier_wait_ms) waited += w;
  wait_share.push_back(p.step_ms > 0.0 ? waited / (p.step_ms * p.threads) : 0.0);
  serial_share.push_back(p.call_ms > 0.0 ? p.serial_ms / p.call_ms : 0.0);
  if (tracing) trace.add_step(start_us, p);
}

void print_serial_share(const StepSamples& samples) {
  std::printf(
      "serial share     %.2f %% of the step() call on one thread whatever the thread count "
      "(plan, contact load when not beside the checks, inertia sums, sleep, recording; the input "
      "checks when on one thread)\n",
      100.0 * median(samples.serial_share));
}

StageTimes stage_medians(const std::vector<StageTimes>& steps) {
  StageTimes out{};
  for (std::size_t k = 0; k < out.size(); ++k) {
    std::vector<double> v;
    v.reserve(steps.size());
    for (const StageTimes& s : steps) v.push_back(s[k]);
    out[k] = median(v);
  }
  return out;
}

void print_stage_table(const StageTimes& medians, double step_ms) {
  std::printf("\n  stage                  ms/step   share\n");
  for (int k = 0; k < kStageCount; ++k) {
    const double v = medians[static_cast<std::size_t>(k)];
    std::printf("  %-22s %8.3f  %5.1f %%\n", stage_name(static_cast<Stage>(k)), v,
                step_ms > 0 ? 100.0 * v / step_ms : 0.0);
  }
}

nlohmann::json stage_json(const StageTimes& medians) {
  nlohmann::json stages;
  for (int k = 0; k < kStageCount; ++k)
    stages[stage_name(static_cast<Stage>(k))] = medians[static_cast<std::size_t>(k)];
  return stages;
}

std::string steps_csv(const std::vector<double>& step_ms, const std::vector<StageTimes>& stages,
                      const std::vector<int>& threads, const std::vector<CsvColumn>& extra) {
  std::string csv = "step,ms";
  for (int k = 0; k < kStageCount; ++k)
    csv += std::string(",") + stage_name(static_cast<Stage>(k)) + "_ms";
  for (const CsvColumn& c : extra) csv += "," + c.name;
  csv += ",threads\n";
  for (std::size_t i = 0; i < step_ms.size() && i < stages.size() && i < threads.size(); ++i) {
    csv += std::to_string(i) + "," + format_number(step_ms[i]);
    for (double v : stages[i]) csv += "," + format_number(v);
    for (const CsvColumn& c : extra)
      csv += "," + format_number(i < c.values->size() ? (*c.values)[i] : kNoValue);
    csv += "," + std::to_string(threads[i]) + "\n";
  }
  return csv;
}

}  // namespace softstep::tool
