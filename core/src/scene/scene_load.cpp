// load_scene: JSON -> a World built through the public API, in the file's order (settings,
// bodies, joints), so the world is what a program making the same calls would get.
#include <fstream>
#include <sstream>

#include "joint_formats.hpp"
#include "json_reader.hpp"
#include "settings_format.hpp"

namespace softstep {

namespace {

using scene::json;
using scene::ObjectReader;

constexpr int kVersion = 1;

BodyType body_type(ObjectReader& fields) {
  const std::string type = fields.text("type");
  if (type == "static") return BodyType::Static;
  if (type == "kinematic") return BodyType::Kinematic;
  if (type == "dynamic") return BodyType::Dynamic;
  scene::fail(fields.source(), fields.path_of("type"),
              "expected \"static\", \"kinematic\" or \"dynamic\"");
}

BodyDef read_body(ObjectReader& fields) {
  BodyDef def;
  def.type = body_type(fields);
  def.position = fields.vec3("position");
  def.orientation = fields.quaternion("orientation", def.orientation);
  def.linear_velocity = fields.vec3("linear_velocity", def.linear_velocity);
  def.angular_velocity = fields.vec3("angular_velocity", def.angular_velocity);
  def.mass = fields.number("mass", def.mass);
  def.inertia = fields.mat3("inertia", def.inertia);
  def.gravity_scale = fields.number("gravity_scale", def.gravity_scale);
  def.linear_damping = fields.number("linear_damping", def.linear_damping);
  def.angular_damping = fields.number("angular_damping", def.angular_damping);
  def.never_sleep = fields.boolean("never_sleep", def.never_sleep);
  fields.no_other_keys();
  return def;
}

std::string element_path(const ObjectReader& parent, const char* key, std::size_t i) {
  return parent.path_of(key) + "/" + std::to_string(i);
}

}  // namespace

World load_scene_text(const std::string& json_text, const std::string& name) {
  json root;
  try {
    root = json::parse(json_text);
  } catch (const json::exception& e) {
    // A syntax error gives its line and column; a number beyond double's range
    // (out_of_range) quotes the number.
    scene::fail(scene::Source{name, nullptr}, "", std::string("not valid JSON: ") + e.what());
  }
  const scene::Source source{name, &root};
  ObjectReader top(source, root, "");
  const double version = top.number("softstep_scene");
  if (version != kVersion)
    scene::fail(source, "/softstep_scene",
                "this softstep reads scene files of version " + std::to_string(kVersion));

  ObjectReader settings_fields(source, top.object("settings"), "/settings");
  const WorldSettings settings = scene::read_settings(settings_fields);
  World world = settings_fields.call([&] { return World(settings); });

  const json& bodies = top.array("bodies");
  std::vector<BodyId> ids;
  ids.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    ObjectReader fields(source, bodies[i], element_path(top, "bodies", i));
    const BodyDef def = read_body(fields);
    ids.push_back(fields.call([&] { return world.create_body(def); }));
  }

  const json& joints = top.array("joints", /*optional=*/true);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    ObjectReader fields(source, joints[i], element_path(top, "joints", i));
    const std::string type = fields.text("type");
    const scene::JointFormat* format = scene::joint_format(type);
    if (format == nullptr) {
      std::string known;
      for (const scene::JointFormat& f : scene::joint_formats())
        known += (known.empty() ? "" : ", ") + std::string(f.name);
      scene::fail(source, fields.path_of("type"), "unknown joint type (known: " + known + ")");
    }
    format->read(world, fields, ids);
  }
  top.no_other_keys();
  return world;
}

World load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) scene::fail(scene::Source{path, nullptr}, "", "cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return load_scene_text(text.str(), path);
}

}  // namespace softstep
