#pragma once

#include <string>
#include <vector>

#include "tool/scene_options.hpp"

namespace softstep::tool {

struct SweepOptions {
  SceneChoice scene;
  std::string out;
  long steps = 60;
  std::vector<long> substeps{1, 2, 4, 8, 16};
  std::vector<long> relax{0, 1, 2, 4};
  std::vector<long> iterations{1};
  std::vector<std::string> warm_start{"on"};
  std::vector<std::string> simd{"best"};
  std::vector<long> threads{1};
  std::vector<long> rigid_hertz{60};
  std::vector<std::string> solver{"iterative"};
  long runs = 3;
  std::string error = "drift";
  int reference_substeps = 64;
  int reference_iterations = 4;
  long probes = 4;
  // The parsed command: whether --steps was given (a recording runs its own steps).
  const CLI::App* command = nullptr;
};

// Declares `softstep sweep` and its options on the tool's app.
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);
// softstep sweep [scene] --out DIR ...: what accuracy costs in time, over a grid of settings.
int sweep_command(const SweepOptions& options);

}  // namespace softstep::tool
