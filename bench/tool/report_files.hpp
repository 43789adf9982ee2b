// Writers for the tool's report files: Chrome trace events, numbers, files. JSON objects are
// built with nlohmann::json where they are filled.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "softstep/profile.hpp"

namespace softstep::tool {

// The median (upper median for an even count), 0 for none.
double median(std::vector<double> values);

// Per-stage times of a run's steps (StepProfile::stage_ms, one array per step): each stage's
// median, the table `softstep profile` prints (share of `step_ms`), and the --csv text.
using StageTimes = std::array<double, kStageCount>;
StageTimes stage_medians(const std::vector<StageTimes>& steps);
void print_stage_table(const StageTimes& medians, double step_ms);
nlohmann::json stage_json(const StageTimes& medians);
// A column of the --csv text beside the stages: one value per step.
struct CsvColumn {
  std::string name;
  const std::vector<double>* values;
};
// `threads`: each step's thread count (the last column); `extra` columns before it.
std::string steps_csv(const std::vector<double>& step_ms, const std::vector<StageTimes>& stages,
                      const std::vector<int>& threads, const std::vector<CsvColumn>& extra = {});

// A number with 10 significant digits for CSV, "null" when it is not finite.
std::string format_number(double value);

// Chrome / Perfetto trace-event JSON: one complete event ("ph": "X") per stage per thread.
class Trace {
 public:
  void add_step(double step_start_us, const StepProfile& profile);
  // A slice of work outside the step's stages (the collision detection, the contact load).
  void add_slice(const char* name, std::size_t thread, double start_us, double duration_us);
  std::string text() const;

 private:
  struct Event {
    const char* name;  // a stage's name or a slice's: static strings
    std::size_t thread;
    double start_us, duration_us;
  };
  std::vector<Event> events_;
};

// What `softstep profile` keeps of each step: its time, its stages, the threads' share of
// time waiting at barriers, and (when traced) its events.
struct StepSamples {
  bool tracing = false;
  std::vector<double> step_ms;
  std::vector<StageTimes> stage_ms;
  std::vector<double> wait_share;
  std::vector<double> serial_share;  // of the step's time, what ran outside the threads' team
  std::vector<int> threads;          // the thread count each step ran on
  long shared_steps = 0;             // steps on more than one thread
  Trace trace;
  // step_ms: the step's time as the caller measured it; start_us: when it started on the
  // trace's clock.
  void add(const StepProfile& profile, double step_ms, double start_us);
};

// The "serial share" line of `softstep profile`: the median share of a step() call that ran
// outside the threads' team (StepProfile::serial_ms).
void print_serial_share(const StepSamples& samples);

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
