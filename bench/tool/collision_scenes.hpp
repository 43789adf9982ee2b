// The contact scenes whose contacts come from a real narrow phase (Bullet's collision module,
// bench/contacts/): `pyramid` and `pile`. Bullet stays a bench-only dependency: the tool links
// softstep_contact_scenes, the library never does. Kept apart from scene_options.cpp so that
// file only names them: their option and their builder live here.
#pragma once

#include <string>

#include "tool/scene_options.hpp"

namespace CLI {
class App;
}

namespace softstep::tool {

bool is_collision_scene(const std::string& scene);

// Declares --base (pyramid) on `command`; pile's --count is the talk scenes' shared option.
void add_collision_scene_options(CLI::App& command, SceneChoice& choice);
// Rejects --base for other scenes (a CLI::ValidationError naming it).
void finish_collision_scene_options(const CLI::App& command, const SceneChoice& choice);

// Replaces `world` by the scene (keeping its settings); SceneRun::contacts runs Bullet's
// narrow phase on the world's poses.
SceneRun build_collision_scene(World& world, const SceneChoice& choice);

}  // namespace softstep::tool
