// Scene files: a world's settings, bodies and joints as JSON, in the API's own names and units
// (README, "Your own scene", has the schema). Loading goes through the public API, so a file
// is held to exactly the checks a program calling create_body and create_*_joint would be.
#pragma once

#include <string>

#include "softstep/errors.hpp"
#include "softstep/world.hpp"

namespace softstep {

// A scene file that cannot be read, is not valid JSON, or holds a value the API refuses.
// field() (from InvalidArgument) is the JSON path of the offending field, e.g.
// "/bodies/3/mass"; the message names the file, that path, the value as the file wrote it and
// the rule it broke.
class SceneFileError : public InvalidArgument {
 public:
  SceneFileError(std::string file, const std::string& json_path, const std::string& message)
      : InvalidArgument(json_path, message), file_(std::move(file)) {}
  const std::string& file() const noexcept { return file_; }

 private:
  std::string file_;
};

// The world the file describes: its settings, then its bodies in file order, then its joints.
// Throws SceneFileError; nothing half-built is returned.
World load_scene(const std::string& path);
// The same from JSON text; `name` stands for the file in error messages.
World load_scene_text(const std::string& json_text, const std::string& name);

// Writes the world's settings, bodies and joints as they are now, as load_scene reads them.
// A scene file holds what the API can create: after steps, joints restart without their warm
// start impulses and every body awake (a fresh world round-trips bit for bit: equal
// state_hash). Throws std::runtime_error naming the path when it cannot be written.
void save_scene(const World& world, const std::string& path);
std::string save_scene_text(const World& world);

}  // namespace softstep
