#pragma once

#include <string>

#include "tool/scene_options.hpp"
#include "tool/view_recorder.hpp"

namespace softstep::tool {

struct ViewOptions {
  SceneChoice scene;
  std::string out;
  long steps = 300;
  ViewLimits limits;
};

// Declares `softstep view` and its options on the tool's app.
CLI::App* add_view_command(CLI::App& app, ViewOptions& options);
// softstep view FILE --out DIR: runs the scene and writes DIR/index.html, which plays it.
int view_command(const ViewOptions& options);

// Adds the subsampling options (--max-bodies, --max-joints, --frames) to a command.
void add_view_limits(CLI::App& command, ViewLimits& limits);

}  // namespace softstep::tool
