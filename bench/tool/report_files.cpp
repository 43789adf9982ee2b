#include "tool/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tool/arguments.hpp"

namespace softstep::tool {

std::string format_number(double value) {
  if (!std::isfinite(value)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", value);
  return b;
}

namespace {
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}
}  // namespace

void JsonObject::add(const std::string& key, double value) {
  members_.push_back(quoted(key) + ": " + format_number(value));
}

void JsonObject::add_string(const std::string& key, const std::string& value) {
  members_.push_back(quoted(key) + ": " + quoted(value));
}

void JsonObject::add_object(const std::string& key, const JsonObject& value) {
  members_.push_back(quoted(key) + ": " + value.text());
}

void JsonObject::add_strings(const std::string& key, const std::vector<std::string>& values) {
  std::string list;
  for (const std::string& v : values) list += (list.empty() ? "" : ", ") + quoted(v);
  members_.push_back(quoted(key) + ": [" + list + "]");
}

void JsonObject::add_objects(const std::string& key, const std::vector<JsonObject>& values) {
  std::string list;
  for (const JsonObject& v : values) list += (list.empty() ? "" : ", ") + v.text();
  members_.push_back(quoted(key) + ": [" + list + "]");
}

std::string JsonObject::text() const {
  std::string out = "{";
  for (std::size_t i = 0; i < members_.size(); ++i) out += (i ? ", " : "") + members_[i];
  return out + "}";
}

void Trace::add_step(double step_start_us, const StepProfile& profile) {
  for (std::size_t t = 0; t < profile.thread_events.size(); ++t) {
    for (const StageEvent& e : profile.thread_events[t]) {
      if (!events_.empty()) events_ += ",\n";
      events_ += "{\"name\": \"" + std::string(stage_name(e.stage)) +
                 "\", \"cat\": \"step\", \"ph\": \"X\", \"ts\": " +
                 format_number(step_start_us + e.start_us) +
                 ", \"dur\": " + format_number(e.end_us - e.start_us) +
                 ", \"pid\": 1, \"tid\": " + std::to_string(t) + "}";
    }
  }
}

std::string Trace::text() const {
  return "{\"traceEvents\": [\n" + events_ + "\n]}\n";
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
