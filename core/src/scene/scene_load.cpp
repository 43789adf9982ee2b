// load_scene: JSON -> a World built through the public API, in the file's order (settings,
// bodies, joints), so the world is what a program making the same calls would get.
#include <fstream>
#include <sstream>

#include "body_format.hpp"
#include "joint_formats.hpp"
#include "json_reader.hpp"
#include "settings_format.hpp"
#include "solver_state.hpp"

namespace softstep {

namespace {

using scene::json;
using scene::ObjectReader;

constexpr int kVersion = 1;

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
  std::vector<double> sleep_times;  // set last: every call on a body starts its rest anew
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    ObjectReader fields(source, bodies[i], element_path(top, "bodies", i));
    const scene::PendingLoads loads = scene::read_pending_loads(fields);
    sleep_times.push_back(scene::read_sleep_time(fields));
    const BodyDef def = scene::read_body(fields);
    ids.push_back(fields.call([&] { return world.create_body(def); }));
    scene::keep_exact_orientation(world, ids.back(), def.orientation);
    // At the centre, so the force adds no moment: the torque saved already holds them all.
    if (!loads.force.isZero(0.0))
      fields.call([&] { world.apply_force(ids.back(), loads.force, def.position); });
    if (!loads.torque.isZero(0.0))
      fields.call([&] { world.apply_torque(ids.back(), loads.torque); });
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
    const scene::JointStateReader state(fields);
    state.apply(world, format->read(world, fields, ids));
  }
  const scene::json& solver_state = top.object("solver_state");
  top.no_other_keys();
  for (std::size_t i = 0; i < ids.size(); ++i) scene::apply_sleep_time(world, ids[i], sleep_times[i]);
  scene::read_world_state(source, solver_state, ids, world);
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
