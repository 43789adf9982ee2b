#include "tool/collision_scenes.hpp"

#include <CLI/CLI.hpp>
#include <memory>
#include <span>

#include "contacts/contact_scenes.hpp"
#include "tool/arguments.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

bool is_collision_scene(const std::string& scene) { return scene == "pyramid" || scene == "pile"; }

void add_collision_scene_options(CLI::App& cmd, SceneChoice& c) {
  cmd.add_option("--base", c.pyramid_base, "pyramid: boxes in the bottom row")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
}

void finish_collision_scene_options(const CLI::App& cmd, const SceneChoice& c) {
  if (cmd.count("--base") > 0 && c.scene != "pyramid")
    throw CLI::ValidationError("--base", "a pyramid option, not for scene " + c.scene);
}

SceneRun build_collision_scene(World& world, const SceneChoice& c) {
  const bool pyramid = c.scene == "pyramid";
  bench::ContactScene built = pyramid ? bench::make_pyramid(c.pyramid_base, world.settings())
                                      : bench::make_pile(c.pile_count, world.settings());
  world = std::move(*built.world);
  SceneRun run;
  run.bodies = built.dynamic;
  run.description =
      pyramid ? "pyramid: base " + std::to_string(c.pyramid_base) + ", " +
                    std::to_string(built.dynamic.size()) +
                    " boxes of 1 m and 100 kg in one vertical plane, each row offset by half a "
                    "box, on a static ground"
              : "pile: " + std::to_string(built.dynamic.size()) +
                    " boxes and spheres of 1 kg dropped into an open box";
  run.description += " (contacts from Bullet's narrow phase, friction " +
                     format_number(built.friction) + ")";
  run.reach = pyramid ? double(c.pyramid_base) : 2.0 + 1.3 * double(c.pile_count) / 64.0;
  run.rows = static_cast<double>(world.step_plan().rows_per_pass);
  // Shared: a SceneRun is copied, and every copy narrows on the one Bullet world.
  std::shared_ptr<bench::BulletContacts> collision = std::move(built.collision);
  run.contacts = [&world, collision, friction = built.friction,
                  restitution = built.restitution] {
    return std::span<const ContactManifold>(collision->find(world, friction, restitution));
  };
  return run;
}

}  // namespace softstep::tool
