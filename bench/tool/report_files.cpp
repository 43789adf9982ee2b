#include "tool/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tool/arguments.hpp"

namespace softstep::tool {

std::string format_number(double value) {
  if (!std::isfinite(value)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", value);
  return b;
}

void Trace::add_step(double step_start_us, const StepProfile& profile) {
  for (std::size_t t = 0; t < profile.thread_events.size(); ++t) {
    for (const StageEvent& e : profile.thread_events[t])
      events_.push_back({e.stage, t, step_start_us + e.start_us, e.end_us - e.start_us});
  }
}

std::string Trace::text() const {
  nlohmann::json events = nlohmann::json::array();
  for (const Event& e : events_) {
    events.push_back({{"name", stage_name(e.stage)},
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

}  // namespace softstep::tool
