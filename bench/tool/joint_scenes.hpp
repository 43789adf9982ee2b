// The scenes of the angular joints in the tool: `hinge-chain`, `prismatic-stack` and `ragdoll`. Kept
// apart from scene_options.cpp so that file only names them: their flags and their builders
// live here.
#pragma once

#include <string>

#include "tool/scene_options.hpp"

namespace CLI {
class App;
}

namespace softstep::tool {

bool is_joint_scene(const std::string& scene);

// Declares the joint scenes' own options (--limit, --motor-torque, --motor-speed, --columns,
// --height) on `command`, parsed into `choice`.
void add_joint_scene_options(CLI::App& command, SceneChoice& choice);
// Once the command line is parsed: rejects those options for other scenes (a
// CLI::ValidationError naming the option), fills choice.hinge / choice.stack from them and
// from the chain's --links / --chains and the spring.
void finish_joint_scene_options(const CLI::App& command, SceneChoice& choice);

SceneRun build_joint_scene(World& world, const SceneChoice& choice);

}  // namespace softstep::tool
