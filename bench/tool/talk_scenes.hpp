// The talk's own scenes in the tool: `vehicle` (cars on wheel joints) and `suspension-bridge`
// (planks hung from cables). Each reports what its springs or its statics promise beside what
// the run measured (SceneRun::reading).
#pragma once

#include <string>

#include "tool/scene_options.hpp"

namespace CLI {
class App;
}

namespace softstep::tool {

bool is_talk_scene(const std::string& scene);

// Declares --count (cars or bridges) on `command`, parsed into `choice`.
void add_talk_scene_options(CLI::App& command, SceneChoice& choice);
// Rejects --count for other scenes and copies it into the scenes' options.
void finish_talk_scene_options(const CLI::App& command, SceneChoice& choice);

SceneRun build_talk_scene(World& world, const SceneChoice& choice);

}  // namespace softstep::tool
