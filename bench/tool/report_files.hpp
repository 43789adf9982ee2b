// Writers for the tool's report files: a small JSON object, Chrome trace events, numbers.
#pragma once

#include <string>
#include <vector>

#include "softstep/profile.hpp"

namespace softstep::tool {

// The median (upper median for an even count), 0 for none.
double median(std::vector<double> values);

// Shortest round-trip form of a number ("%.17g" trimmed), for JSON and CSV.
std::string format_number(double value);

class JsonObject {
 public:
  void add(const std::string& key, double value);
  void add_string(const std::string& key, const std::string& value);
  void add_object(const std::string& key, const JsonObject& value);
  void add_strings(const std::string& key, const std::vector<std::string>& values);
  void add_objects(const std::string& key, const std::vector<JsonObject>& values);
  std::string text() const;

 private:
  std::vector<std::string> members_;
};

// Chrome / Perfetto trace-event JSON: one complete event ("ph": "X") per stage per thread.
class Trace {
 public:
  void add_step(double step_start_us, const StepProfile& profile);
  std::string text() const;

 private:
  std::string events_;
};

// Throws std::runtime_error naming the path when the file cannot be written.
void write_file(const std::string& path, const std::string& text);

// Checked before a run, so that a run of minutes does not end in "cannot write": throw
// UsageError naming the flag and the path when a file cannot be created there (an existing
// file is left as it is), or the directory cannot be created and written into.
void check_writable_file(const std::string& flag, const std::string& path);
void check_writable_directory(const std::string& flag, const std::string& directory);

}  // namespace softstep::tool
