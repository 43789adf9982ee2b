// save_scene: a World -> JSON that load_scene reads back into the same world. One body or
// joint per line, so that a 100,000-body file stays readable and diffs line by line.
#include <fstream>
#include <stdexcept>

#include "joint_formats.hpp"
#include "settings_format.hpp"
#include "softstep/scene_file.hpp"

namespace softstep {

namespace {

const char* body_type_name(BodyType type) {
  return type == BodyType::Static      ? "static"
         : type == BodyType::Kinematic ? "kinematic"
                                       : "dynamic";
}

nlohmann::json body_json(const BodyState& b) {
  const Quaternion& q = b.orientation;
  nlohmann::json j = {{"type", body_type_name(b.type)},
                      {"position", scene::vector_json(b.position)},
                      {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                      {"linear_velocity", scene::vector_json(b.linear_velocity)},
                      {"angular_velocity", scene::vector_json(b.angular_velocity)}};
  // Static and kinematic bodies have no mass (the API ignores one given).
  if (b.type == BodyType::Dynamic) {
    j["mass"] = b.mass;
    j["inertia"] = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) j["inertia"].push_back(scene::vector_json(b.inertia.row(r)));
  }
  j["gravity_scale"] = b.gravity_scale;
  j["linear_damping"] = b.linear_damping;
  j["angular_damping"] = b.angular_damping;
  j["never_sleep"] = b.never_sleep;
  return j;
}

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
  for (BodyId id : bodies) body_lines.push_back(body_json(world.body(id)).dump());

  const scene::BodyIndex index(bodies);
  std::vector<std::string> joint_lines;
  for (JointId id : world.joint_ids()) {
    const scene::JointFormat& format = scene::joint_format(world.joint_type(id));
    nlohmann::json j = {{"type", format.name}};
    format.write(world, id, index, j);
    joint_lines.push_back(j.dump());
  }

  std::string out = "{\n  \"softstep_scene\": 1,\n  \"settings\": " +
                    scene::settings_json(world.settings()).dump() + ",\n";
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
