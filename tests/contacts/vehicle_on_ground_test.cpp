// The vehicle scene on the ground (bench/scenes/vehicle_scene.hpp): its wheels touch a static
// plane through the scene's own contacts (a sphere on a plane, one point per wheel), so the
// car rests on its springs and its tyres (the contact spring), bounces, and is pushed forward
// by its wheel motors through friction.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "frame_constants.hpp"
#include "scenes/vehicle_scene.hpp"

namespace softstep {
namespace {

using test::kDt;

// The bounce and the ride height are watched through to rest: nothing may fall asleep.
WorldSettings awake() {
  WorldSettings s;
  s.sleeping = false;
  return s;
}

struct CarRun {
  World world;
  scenes::VehicleScene scene;
  std::vector<ContactManifold> contacts;
  explicit CarRun(const scenes::VehicleOptions& o, WorldSettings settings = {})
      : world(settings), scene(scenes::build_vehicle(world, o)) {}
  void step() {
    scenes::vehicle_contacts(world, scene, contacts);
    world.step(kDt, contacts);
  }
  // The first car's chassis height now and after each of `steps` steps.
  std::vector<double> chassis_heights(int steps) {
    const BodyId chassis = scene.cars[0].chassis;
    std::vector<double> heights{world.body(chassis).position.y()};
    for (int i = 0; i < steps; ++i) {
      step();
      heights.push_back(world.body(chassis).position.y());
    }
    return heights;
  }
};

// A 1,200 kg car on four 2 Hz, 0.3 damping-ratio springs and 20 kg wheels, released at rest
// with its springs unloaded and its wheels just touching the ground. At rest the soft step's
// impulses are the static forces exactly (softness.hpp: with v = 0 the row's impulse per
// sub-step is h k (-C)), so:
// - the spring travels m_s g / k = g / omega^2 (6.2 cm; wheel.hpp);
// - the tyre, a contact spring of WorldSettings::contact.hertz on the contact row's effective
//   mass (the wheel's 20 kg: the point is straight below the centre, r x n = 0), is pressed in
//   by the corner's weight (m_s + m_w) g: (m_s + m_w) g / (m_w omega_c^2), 4.4 mm at 30 Hz;
// - the chassis centre rides at its start height less both.
// The rows are float: the anchors (|r| <= 1 m) and separations carry ~1e-7 m of rounding, the
// impulses ~1e-7 relative (6e-9 m of the 62 mm travel), so 1e-5 m leaves a wide margin and is
// still 440 times smaller than the tyre's compression a ride height without it would miss.
// After 7.5 s the bounce (amplitude 6 cm, decaying as e^(-zeta omega t) = e^-28) is gone.
// The bounce (first 2.5 s) is the springs' 2 Hz within 3 %: the tyre (k_c = m_w omega_c^2 =
// 710 kN/m, 15 times the 47 kN/m spring, and heavily damped, contact damping ratio 10) in
// series lowers it by about 1 % (the quarter car's complex stiffness at 2 Hz).
TEST(CarOnTheGround, RestsAtTheSpringsAndTyresDeflectionAndBouncesAtTheSpringsHertz) {
  scenes::VehicleOptions o;
  o.speed = 0.0;
  o.motor_torque = 0.0;
  const WorldSettings settings = awake();
  CarRun run(o, settings);
  const scenes::Car& car = run.scene.cars[0];
  std::vector<double> heights = run.chassis_heights(450);
  const double g = 9.81, m_s = o.chassis_mass / 4.0, m_w = o.wheel_mass;
  const double omega = 2.0 * std::numbers::pi * o.hertz;
  const double omega_c = 2.0 * std::numbers::pi * settings.contact.hertz;
  const double tyre = (m_s + m_w) * g / (m_w * omega_c * omega_c);
  EXPECT_NEAR(run.scene.promised_tyre_compression, tyre, 1e-12);
  EXPECT_NEAR(run.scene.promised_ride_height, o.wheel_radius + 0.3 - g / (omega * omega) - tyre,
              1e-12);
  EXPECT_NEAR(run.world.joint_reading(car.wheel_joints[0]).position, g / (omega * omega), 1e-5);
  EXPECT_NEAR(run.world.body(car.wheels[0]).position.y(), o.wheel_radius - tyre, 1e-5);
  EXPECT_NEAR(heights.back(), run.scene.promised_ride_height, 1e-5);
  heights.resize(151);
  const scenes::Bounce b = scenes::measure_bounce(heights, run.scene.promised_ride_height, kDt);
  EXPECT_NEAR(b.hertz, o.hertz, 0.03 * o.hertz);
}

// The same car rolling at 10 m/s from the start (its motors holding that speed): its wheels
// turn 0.48 rad per step, yet it rides at the resting car's height within the resting car's
// 1e-5 m and bounces at the springs' 2 Hz within 3 %. Its wheel contacts are round (the
// wheel's centre and radius, sphere_contacts.hpp), so the solver follows the centre, which
// does not rise as the wheel turns; given by the wheel's lowest point (the contacts' only form
// before radii) that point rose r (1 - cos 0.48) = 3.9 cm within each step and the car rode
// 3.2 cm low, bouncing 5 % slow.
TEST(CarOnTheGround, DrivingAtTenMetresASecondRidesAndBouncesAsAtRest) {
  scenes::VehicleOptions o;
  o.speed = 10.0;
  CarRun run(o, awake());
  std::vector<double> heights = run.chassis_heights(450);
  EXPECT_NEAR(run.world.body(run.scene.cars[0].chassis).linear_velocity.x(), o.speed,
              1e-3 * o.speed);
  EXPECT_NEAR(heights.back(), run.scene.promised_ride_height, 1e-5);
  heights.resize(151);
  const scenes::Bounce b = scenes::measure_bounce(heights, run.scene.promised_ride_height, kDt);
  EXPECT_NEAR(b.hertz, o.hertz, 0.03 * o.hertz);
}

// Started at rest with its motors set to 10 m/s, the car is pushed by the wheels' friction
// (mu = 1 carries up to 3.1 kN per wheel, the motors ask 200 N m / 0.35 m = 571 N), so its
// acceleration is what the motors' torque cap allows: 4 tau / r spent on the car's mass and
// its wheels' spin, a = (4 tau / r) / (M + 4 m_w + 4 I / r^2) with I = m_w r^2 / 2:
// 2,286 N / 1,320 kg = 1.73 m/s^2, 10 m/s after 5.8 s. After 3 s it has gone a t^2 / 2 =
// 7.8 m: never further (the cap; sub-stepped symplectic Euler moves a h^2 k (k + 1) / 2 in
// k sub-steps of h, a t (t + h) / 2, and float rows round the cap by ~1e-7), and not 3 % less
// (what friction or a sinking wheel would cost); after 10 s it cruises at the motors' 10 m/s.
TEST(CarOnTheGround, ItsMotorsDriveItForwardAsFastAsTheirTorqueAllows) {
  scenes::VehicleOptions o;
  o.speed = 10.0;
  o.start_rolling = false;
  CarRun run(o);
  const scenes::Car& car = run.scene.cars[0];
  const double start = run.world.body(car.chassis).position.x();
  const double r = o.wheel_radius;
  const double a = 4.0 * o.motor_torque / r /
                   (o.chassis_mass + 4.0 * o.wheel_mass + 4.0 * 0.5 * o.wheel_mass);
  for (int i = 1; i <= 600; ++i) {
    run.step();
    const double t = i * kDt;
    const double travelled = run.world.body(car.chassis).position.x() - start;
    if (t <= 5.0) {
      const double h = kDt / run.world.settings().substeps;
      EXPECT_LE(travelled, 0.5 * a * t * (t + h) * (1.0 + 1e-5)) << "at " << t << " s";
    }
    if (i == 180) {
      EXPECT_GE(travelled, 0.97 * 0.5 * a * t * t);
    }
  }
  EXPECT_NEAR(run.world.body(car.chassis).linear_velocity.x(), o.speed, 0.01 * o.speed);
}

}  // namespace
}  // namespace softstep
