#pragma once

#include <string>

namespace CLI {
class App;
}

namespace softstep::tool {

struct ReplayOptions {
  std::string path;
};

// Declares `softstep replay` on the tool's app.
CLI::App* add_replay_command(CLI::App& app, ReplayOptions& options);
// softstep replay FILE: re-runs a recording, checking every step's motion hash.
int replay_command(const ReplayOptions& options);

}  // namespace softstep::tool
