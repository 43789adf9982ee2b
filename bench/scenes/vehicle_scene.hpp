// Cars on rails: each a chassis on four wheel joints. No contacts exist yet, so each wheel
// rides on a rail: a second wheel joint, from the static world, whose free travel is along x
// (no spring), so the wheel rolls along x and spins, its centre at axle height. The rail is a
// rigid row, a 60 Hz spring on the wheel's mass (WorldSettings::rigid_hertz) in series with
// the suspension: it lowers the bounce by k_spring / (2 k_rail), 0.8 % for 20 kg wheels. The cars start with their
// springs unloaded, rolling at `speed`, their wheels spun by the wheel motors at the rolling
// speed; under gravity each chassis settles g / (2 pi hertz)^2 lower, bouncing at `hertz` with
// `damping_ratio` (wheel.hpp: the springs' frequency refers to the sprung mass, a quarter of
// the chassis). Cars stand 4 m apart along z. Used by `softstep profile vehicle` and the wheel
// joint's tests.
#pragma once

#include <array>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct VehicleOptions {
  int cars = 1;                 // >= 1
  double chassis_mass = 1200.0;  // kg, a box of 4.2 x 0.6 x 1.8 m
  double wheel_mass = 20.0;     // kg, a disc of radius wheel_radius
  double wheel_radius = 0.35;   // m
  double wheelbase = 2.8;       // m, front to rear axle
  double track = 1.6;           // m, left to right wheel
  double hertz = 2.0;           // suspension
  double damping_ratio = 0.3;
  double speed = 10.0;  // m/s along +x at the start
  double motor_torque = 200.0;  // N m per wheel motor, 0: wheels spin freely
  double steering = 0.0;        // rad, the front wheels (the carriages keep the car on its rail)
  // Every n-th car (0, n, 2n, ...) gets its suspension as Spring::absolute(k, c) with the k and
  // c the relative spring has on its sprung mass: the same car in N/m. 0: none.
  int absolute_every = 0;
};

struct Car {
  BodyId chassis;
  std::array<BodyId, 4> wheels;      // front left, front right, rear left, rear right
  std::array<JointId, 4> rails;
  std::array<JointId, 4> wheel_joints;
  double start_height = 0.0;  // m, the chassis centre with the springs unloaded
};

struct VehicleScene {
  BodyId ground;
  std::vector<Car> cars;
  std::vector<JointId> joints;  // every joint
  // What the springs promise: the chassis rides g / omega^2 below its start height.
  double promised_sag = 0.0;  // m
};

VehicleScene build_vehicle(World& world, const VehicleOptions& options);

// The frequency (Hz) and damping ratio of a decaying oscillation about `rest`, from its
// samples every dt: the damped period from upward crossings of rest, the decay from the
// ratio of successive peaks above it (log decrement). Zero when fewer than two periods.
struct Bounce {
  double hertz = 0.0;
  double damping_ratio = 0.0;
};
Bounce measure_bounce(const std::vector<double>& samples, double rest, double dt);

}  // namespace softstep::scenes
