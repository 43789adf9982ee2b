// save_scene: a World -> JSON that load_scene reads back into the same world. One body or
// joint per line, so that a 100,000-body file stays readable and diffs line by line.
#include <fstream>
#include <stdexcept>

#include "body_format.hpp"
#include "joint_formats.hpp"
#include "settings_format.hpp"
#include "solver_state.hpp"
#include "softstep/scene_file.hpp"

namespace softstep {

namespace {

void append_list(std::string& out, const char* key, const std::vector<std::string>& lines,
                 bool last) {
  out += "  \"" + std::string(key) + "\": [";
  for (std::size_t i = 0; i < lines.size(); ++i) out += (i ? ",\n    " : "\n    ") + lines[i];
  out += lines.empty() ? "]" : "\n  ]";
  out += last ? "\n" : ",\n";
}

}  // namespace

std::string save_scene_text(const World& world) {
  const std::vector<BodyId> bodies = world.body_ids();
  std::vector<std::string> body_lines;
  body_lines.reserve(bodies.size());
  for (BodyId id : bodies) {
    const BodyState state = world.body(id);
    nlohmann::json body = scene::body_json(scene::body_def(state));
    scene::write_pending_loads(state, body);
    scene::write_body_state(world, id, body);
    body_lines.push_back(body.dump());
  }

  const scene::BodyIndex index(bodies);
  std::vector<std::string> joint_lines;
  for (JointId id : world.joint_ids()) {
    const scene::JointFormat& format = scene::joint_format(world.joint_type(id));
    nlohmann::json j = {{"type", format.name}};
    format.write(world, id, index, j);
    scene::write_joint_state(world, id, j);
    joint_lines.push_back(j.dump());
  }

  std::string out = "{\n  \"softstep_scene\": 1,\n  \"settings\": " +
                    scene::settings_json(world.settings()).dump() + ",\n";
  const std::string state = scene::world_state_text(world, index);
  if (!state.empty()) out += "  \"solver_state\": " + state + ",\n";
  append_list(out, "bodies", body_lines, false);
  append_list(out, "joints", joint_lines, true);
  return out + "}\n";
}

void save_scene(const World& world, const std::string& path) {
  const std::string text = save_scene_text(world);
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write the scene file " + path);
}

}  // namespace softstep
