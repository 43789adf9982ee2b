// Writers for the tool's report files: Chrome trace events, numbers, files. JSON objects are
// built with nlohmann::json where they are filled.
#pragma once

#include <string>
#include <vector>

#include "softstep/profile.hpp"

namespace softstep::tool {

// The median (upper median for an even count), 0 for none.
double median(std::vector<double> values);

// A number with 10 significant digits for CSV, "null" when it is not finite.
std::string format_number(double value);

// Chrome / Perfetto trace-event JSON: one complete event ("ph": "X") per stage per thread.
class Trace {
 public:
  void add_step(double step_start_us, const StepProfile& profile);
  std::string text() const;

 private:
  struct Event {
    Stage stage;
    std::size_t thread;
    double start_us, duration_us;
  };
  std::vector<Event> events_;
};

// Text made safe inside HTML or SVG: <, > and & escaped.
std::string markup_text(const std::string& text);

// Throws std::runtime_error naming the path when the file cannot be written.
void write_file(const std::string& path, const std::string& text);

// Checked before a run, so that a run of minutes does not end in "cannot write": throw
// UsageError naming the flag and the path when a file cannot be created there (an existing
// file is left as it is), or the directory cannot be created and written into.
void check_writable_file(const std::string& flag, const std::string& path);
void check_writable_directory(const std::string& flag, const std::string& directory);

}  // namespace softstep::tool
