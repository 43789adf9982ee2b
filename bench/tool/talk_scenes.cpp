#include "tool/talk_scenes.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include "tool/report_files.hpp"

namespace softstep::tool {

bool is_talk_scene(const std::string& scene) {
  return scene == "vehicle" || scene == "suspension-bridge";
}

void add_talk_scene_options(CLI::App& cmd, SceneChoice& c) {
  cmd.add_option("--count", c.count,
                 "ragdoll: ragdolls of 16 bodies (default 1); vehicle: cars (default 100); "
                 "suspension-bridge: bridges (default 10); pile: bodies dropped (default 1000)")
      ->check(whole_in(1, 10000000));
  cmd.add_option("--speed", c.vehicle.speed,
                 "vehicle: the cars' speed, m/s, their wheel motors' target (default 10)")
      ->check(CLI::Range(0.0, 100.0));
}

void finish_talk_scene_options(const CLI::App& cmd, SceneChoice& c) {
  if (cmd.count("--count") > 0 && !is_talk_scene(c.scene) && c.scene != "ragdoll" &&
      c.scene != "pile")
    throw CLI::ValidationError(
        "--count", "a ragdoll, vehicle, suspension-bridge or pile option, not for scene " + c.scene);
  if (cmd.count("--speed") > 0 && c.scene != "vehicle")
    throw CLI::ValidationError("--speed", "a vehicle option, not for scene " + c.scene);
  const bool given = cmd.count("--count") > 0;
  c.ragdoll.count = given ? c.count : 1;
  c.vehicle.cars = given ? c.count : 100;
  c.suspension.bridges = given ? c.count : 10;
  c.pile_count = given ? c.count : 1000;
}

namespace {

SceneRun vehicle_run(World& world, const scenes::VehicleOptions& o) {
  SceneRun run;
  auto built = std::make_shared<const scenes::VehicleScene>(scenes::build_vehicle(world, o));
  run.joints = built->joints;
  for (const scenes::Car& car : built->cars) {
    run.bodies.push_back(car.chassis);
    run.bodies.insert(run.bodies.end(), car.wheels.begin(), car.wheels.end());
  }
  run.description = "vehicle: " + std::to_string(o.cars) + " cars of " +
                    format_number(o.chassis_mass) + " kg on four wheel joints (springs " +
                    format_number(o.hertz) + " Hz, ratio " + format_number(o.damping_ratio) +
                    ", wheels " + format_number(o.wheel_mass) + " kg), driven at " +
                    format_number(o.speed) + " m/s on the ground (contacts, friction " +
                    format_number(o.tyre_friction) + ")";
  run.reach = 1.0;
  auto manifolds = std::make_shared<std::vector<ContactManifold>>();
  run.contacts = [&world, built, manifolds] {
    scenes::vehicle_contacts(world, *built, *manifolds);
    return std::span<const ContactManifold>(*manifolds);
  };
  // The first car's chassis height after every step; the reading compares its bounce (the
  // first 2.5 s) and where it rides (the last step) with what the springs promise.
  auto heights = std::make_shared<std::vector<double>>();
  const scenes::Car car = built->cars.front();
  heights->push_back(world.body(car.chassis).position.y());
  run.after_step = [&world, heights, chassis = car.chassis] {
    heights->push_back(world.body(chassis).position.y());
  };
  const double start_x = world.body(car.chassis).position.x();
  const auto bounce = [heights] {
    if (heights->size() < 200) return scenes::Bounce{};
    std::vector<double> window(heights->begin(), heights->begin() + 151);
    return scenes::measure_bounce(window, heights->back(), 1.0 / 60.0);
  };
  run.readings = [heights, built, o, bounce] {
    SceneReadings r;
    r.ride_height_error_m = heights->back() - built->promised_ride_height;
    const scenes::Bounce b = bounce();
    if (b.hertz > 0.0) {
      r.bounce_hz = b.hertz;
      r.bounce_error = (b.hertz - o.hertz) / o.hertz;
    }
    return r;
  };
  run.reading = [&world, heights, built, car, o, bounce, start_x] {
    const double travel = world.joint_reading(car.wheel_joints[0]).position;
    const double sag = built->promised_sag;
    std::string text = "ride height      " + format_number(heights->back()) +
                       " m, promised " + format_number(built->promised_ride_height) +
                       " m (spring m_s g / k = " + format_number(sag) +
                       " m, tyre (m_s + m_w) g / k_contact = " +
                       format_number(built->promised_tyre_compression) + " m): off by " +
                       format_number(heights->back() - built->promised_ride_height) + " m\n" +
                       "spring travel    " + format_number(travel) + " m (" +
                       format_number(100.0 * (travel - sag) / sag) + " % from m_s g / k)\n";
    const BodyState chassis = world.body(car.chassis);
    text += "driven           " + format_number(chassis.position.x() - start_x) + " m along x, " +
            format_number(chassis.linear_velocity.x()) + " m/s (motors' target " +
            format_number(o.speed) + " m/s)\n";
    const scenes::Bounce b = bounce();
    if (b.hertz == 0.0)
      return text + "bounce           (none measured: it needs 200 steps and two periods)\n";
    return text + "bounce           " + format_number(b.hertz) + " Hz, damping ratio " +
           format_number(b.damping_ratio) + " (springs: " + format_number(o.hertz) + " Hz, " +
           format_number(o.damping_ratio) + ")\n";
  };
  return run;
}

SceneRun suspension_run(World& world, const scenes::SuspensionBridgeOptions& o) {
  SceneRun run;
  auto built =
      std::make_shared<scenes::SuspensionBridgeScene>(scenes::build_suspension_bridge(world, o));
  run.joints = built->joints;
  run.bodies = built->nodes;
  run.bodies.insert(run.bodies.end(), built->planks.begin(), built->planks.end());
  for (const scenes::Car& cart : built->carts) {
    run.bodies.push_back(cart.chassis);
    run.bodies.insert(run.bodies.end(), cart.wheels.begin(), cart.wheels.end());
  }
  run.description = "suspension-bridge: " + std::to_string(o.bridges) + " bridges of " +
                    std::to_string(o.stations + 1) + " planks (" + format_number(o.plank_mass) +
                    " kg) on revolute and ball joints under two cables of distance joints, a " +
                    format_number(o.load_mass) + " kg cart crossing at " +
                    format_number(o.cart_speed) + " m/s on contacts";
  run.reach = built->static_sag + 2.0;
  auto manifolds = std::make_shared<std::vector<ContactManifold>>();
  run.contacts = [&world, built, manifolds] {
    scenes::bridge_contacts(world, *built, *manifolds);
    return std::span<const ContactManifold>(*manifolds);
  };
  auto steps = std::make_shared<long>(0);
  run.after_step = [&world, built, steps] {
    scenes::track_carts(world, *built, static_cast<double>(++*steps) / 60.0);
  };
  run.readings = [built] {
    SceneReadings r;
    const scenes::Crossing& c = built->crossings.front();
    r.sag_error = (c.sag_at_mid - built->loaded_static_sag) / built->loaded_static_sag;
    r.crossing_s = c.crossing_s();
    return r;
  };
  run.reading = [&world, built, o] {
    const scenes::Crossing& c = built->crossings.front();
    const double sag = scenes::measured_sag(world, *built, o);
    std::string text = "sag              " + format_number(sag) + " m now, unloaded static solution " +
                       format_number(built->static_sag) + " m\n";
    if (std::isnan(c.sag_at_mid)) {
      text += "sag under cart   (the cart has not reached mid-span: it is at x = " +
              format_number(world.body(built->carts.front().chassis).position.x()) + " m of " +
              format_number(built->span) + ")\n";
    } else {
      text += "sag under cart   " + format_number(c.sag_at_mid) +
              " m at mid-span, static solution " + format_number(built->loaded_static_sag) +
              " m (" +
              format_number(100.0 * (c.sag_at_mid - built->loaded_static_sag) /
                            built->loaded_static_sag) +
              " %)\n";
    }
    text += "crossing         " +
            (std::isnan(c.left_s) ? std::string("not across yet")
                                  : format_number(c.crossing_s()) + " s from tower to tower (" +
                                        format_number(built->span) + " m at a target " +
                                        format_number(o.cart_speed) + " m/s)") +
            "\n";
    return text;
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
