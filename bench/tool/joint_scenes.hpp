// The scenes of the angular joints in the tool: `hinge-chain` and `prismatic-stack`. Kept
// apart from scene_options.cpp so that file only names them: their flags and their builders
// live here.
#pragma once

#include <string>

#include "tool/scene_options.hpp"

namespace softstep::tool {

extern const char* const kJointSceneUsage;

bool is_joint_scene(const std::string& scene);

// Takes the joint scenes' own flags (rejecting them for other scenes) and fills
// choice.hinge / choice.stack; reads the chain's --links / --chains and the spring.
void take_joint_scene_options(Arguments& args, SceneChoice& choice);

SceneRun build_joint_scene(World& world, const SceneChoice& choice);

}  // namespace softstep::tool
