#pragma once

#include <string>

#include "tool/scene_options.hpp"

namespace softstep::tool {

struct ProfileOptions {
  SceneChoice scene;
  long steps = 300;
  WorldSettings settings;
  std::string simd = "best";
  std::string solver = "iterative";
  bool threads_fixed = false;
  bool no_warm_start = false, no_sleep = false, general = false, show_plan = false;
  bool no_friction_while_solving = false;
  std::string json_path, csv_path, trace_path, save_path, record_path;
  std::string recording_overhead_path;  // --recording-overhead (tool/recording_overhead.hpp)
  double bandwidth_gbps = 0.0;  // a triad bandwidth for the memory section's fractions (0: none)
  // The parsed command: which solver options were given (a scene file's settings hold
  // otherwise).
  const CLI::App* command = nullptr;
};

// Declares `softstep profile` and its options on the tool's app.
CLI::App* add_profile_command(CLI::App& app, ProfileOptions& options);
// softstep profile [chain] --links N --chains M ... : runs a scene and reports its cost.
int profile_command(ProfileOptions options);

}  // namespace softstep::tool
