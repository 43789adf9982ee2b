#include "tool/talk_scenes.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <memory>
#include <numbers>

#include "tool/report_files.hpp"

namespace softstep::tool {

bool is_talk_scene(const std::string& scene) {
  return scene == "vehicle" || scene == "suspension-bridge";
}

void add_talk_scene_options(CLI::App& cmd, SceneChoice& c) {
  cmd.add_option("--count", c.count,
                 "ragdoll: ragdolls of 16 bodies (default 1); vehicle: cars (default 100); "
                 "suspension-bridge: bridges (default 10)")
      ->check(whole_in(1, 10000000));
}

void finish_talk_scene_options(const CLI::App& cmd, SceneChoice& c) {
  if (cmd.count("--count") > 0 && !is_talk_scene(c.scene) && c.scene != "ragdoll")
    throw CLI::ValidationError(
        "--count", "a ragdoll, vehicle or suspension-bridge option, not for scene " + c.scene);
  const bool given = cmd.count("--count") > 0;
  c.ragdoll.count = given ? c.count : 1;
  c.vehicle.cars = given ? c.count : 100;
  c.suspension.bridges = given ? c.count : 10;
}

namespace {

SceneRun vehicle_run(World& world, const scenes::VehicleOptions& o) {
  SceneRun run;
  const scenes::VehicleScene built = scenes::build_vehicle(world, o);
  run.joints = built.joints;
  for (const scenes::Car& car : built.cars) {
    run.bodies.push_back(car.chassis);
    run.bodies.insert(run.bodies.end(), car.wheels.begin(), car.wheels.end());
  }
  run.description = "vehicle: " + std::to_string(o.cars) + " cars of " +
                    format_number(o.chassis_mass) + " kg on four wheel joints (springs " +
                    format_number(o.hertz) + " Hz, ratio " + format_number(o.damping_ratio) +
                    ", wheels " + format_number(o.wheel_mass) + " kg), rolling at " +
                    format_number(o.speed) + " m/s on rails";
  run.reach = 1.0;
  // The first car's chassis height after every step; the reading compares its bounce (the
  // first 2.5 s) and where it rides (the last step) with what the springs promise.
  auto heights = std::make_shared<std::vector<double>>();
  const scenes::Car car = built.cars.front();
  heights->push_back(world.body(car.chassis).position.y());
  run.after_step = [&world, heights, chassis = car.chassis] {
    heights->push_back(world.body(chassis).position.y());
  };
  run.reading = [&world, heights, car, o, sag = built.promised_sag] {
    const double travel = world.joint_reading(car.wheel_joints[0]).position;
    std::string text = "ride             spring travel " + format_number(travel) +
                       " m, promised g / omega^2 = " + format_number(sag) + " m (" +
                       format_number(100.0 * (travel - sag) / sag) + " %)\n";
    if (heights->size() < 200) return text + "bounce           (needs 200 steps)\n";
    std::vector<double> window(heights->begin(), heights->begin() + 151);
    const scenes::Bounce b = scenes::measure_bounce(window, heights->back(), 1.0 / 60.0);
    return text + "bounce           " + format_number(b.hertz) + " Hz, damping ratio " +
           format_number(b.damping_ratio) + " (springs: " + format_number(o.hertz) + " Hz, " +
           format_number(o.damping_ratio) + ")\n";
  };
  return run;
}

SceneRun suspension_run(World& world, const scenes::SuspensionBridgeOptions& o) {
  SceneRun run;
  const scenes::SuspensionBridgeScene built = scenes::build_suspension_bridge(world, o);
  run.joints = built.joints;
  run.bodies = built.nodes;
  run.bodies.insert(run.bodies.end(), built.planks.begin(), built.planks.end());
  run.description = "suspension-bridge: " + std::to_string(o.bridges) + " bridges of " +
                    std::to_string(o.stations) + " planks (" + format_number(o.plank_mass) +
                    " kg) on revolute joints under two cables of distance joints, a " +
                    format_number(o.load_mass) + " kg load at mid-span";
  run.reach = built.static_sag + 2.0;
  run.reading = [&world, built, o] {
    const double sag = scenes::measured_sag(world, built, o);
    return "sag              " + format_number(sag) + " m, static solution " +
           format_number(built.static_sag) + " m (" +
           format_number(100.0 * (sag - built.static_sag) / built.static_sag) + " %)\n";
  };
  return run;
}

}  // namespace

SceneRun build_talk_scene(World& world, const SceneChoice& c) {
  SceneRun run = c.scene == "vehicle" ? vehicle_run(world, c.vehicle)
                                      : suspension_run(world, c.suspension);
  run.rows = static_cast<double>(world.step_plan().rows_per_pass);
  return run;
}

}  // namespace softstep::tool
