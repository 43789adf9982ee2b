// Cars on the ground: each a chassis on four wheel joints whose wheels touch a static ground
// (the plane y = 0) through contacts the scene computes itself each step (vehicle_contacts:
// a wheel is a sphere on the plane, sphere_contacts.hpp; friction `tyre_friction`), so the
// wheel motors push the car. The cars start with their springs unloaded and their wheels
// just touching, rolling at `speed` (or at rest, `start_rolling` false), their motors holding
// (or driving them up to) the rolling speed; cars stand 4 m apart along z and drive along +x.
// Used by `softstep profile vehicle`, the wheel joint's tests, and (build_car) the cart that
// crosses the suspension bridge.
//
// What the springs promise (vehicle.promised_*): under gravity the chassis settles by the
// spring's static deflection m_s g / k = g / (2 pi hertz)^2 (wheel.hpp: the springs'
// frequency refers to the sprung mass m_s, a quarter of the chassis), and the tyre, the contact
// spring (WorldSettings::contact, relative to the contact row's effective mass, the wheel's
// mass m_w: the point is straight below the centre, so the wheel's inertia does not enter),
// is pressed in by the corner's weight: (m_s + m_w) g / (m_w (2 pi contact hertz)^2), 4.4 mm
// at the default 30 Hz for 20 kg wheels. Both are exact at rest (the soft step's impulse is
// then the static force). The tyre in series with the suspension lowers the bounce (the ride
// rate): how much the reading shows.
//
// `on_rails` keeps the scene's first form, from before contacts: each wheel rides on a second,
// spring-less wheel joint from the world whose free travel is along x. The wheel joint's own
// tests use it: they hold the joint to its promise (2 Hz whatever the wheel weighs) without
// the tyre's compliance in series, which a 10 kg wheel on 30 Hz contacts would add.
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
  double speed = 10.0;  // m/s along +x: the wheel motors' target (and the start speed)
  bool start_rolling = true;    // false: the cars start at rest, their motors drive them
  double motor_torque = 200.0;  // N m per wheel motor, 0: wheels spin freely
  double steering = 0.0;        // rad, the front wheels
  double tyre_friction = 1.0;   // the wheel-ground contacts' Coulomb coefficient
  bool on_rails = false;        // the wheels on rails instead of the ground (see above)
  // Every n-th car (0, n, 2n, ...) gets its suspension as Spring::absolute(k, c) with the k and
  // c the relative spring has on its sprung mass: the same car in N/m. 0: none.
  int absolute_every = 0;
};

struct Car {
  BodyId chassis;
  std::array<BodyId, 4> wheels;      // front left, front right, rear left, rear right
  std::array<JointId, 4> wheel_joints;
  std::array<JointId, 4> rails;      // on_rails only
  double start_height = 0.0;  // m, the chassis centre with the springs unloaded
};

// One car on four wheel joints, its wheels' lowest points at `ground_point` (the point under
// the car's centre) + (+-wheelbase / 2, 0, +-track / 2), facing +x. Its joints are appended
// to `joints`.
Car build_car(World& world, const VehicleOptions& options, const Eigen::Vector3d& ground_point,
              std::vector<JointId>& joints);

struct VehicleScene {
  BodyId ground;
  std::vector<Car> cars;
  std::vector<JointId> joints;  // every joint
  bool on_rails = false;
  double wheel_radius = 0.0;
  double tyre_friction = 0.0;
  // What the springs and tyres promise for a car at rest (see above), m.
  double promised_sag = 0.0;              // the spring's travel, m_s g / k
  double promised_tyre_compression = 0.0;  // (m_s + m_w) g / (m_w omega_contact^2); 0 on rails
  double promised_ride_height = 0.0;      // the chassis centre: start - the two above
};

VehicleScene build_vehicle(World& world, const VehicleOptions& options);

// The wheels' contacts with the ground for the world's poses now, in a fixed order (car by
// car, wheel by wheel), into `out` (cleared first; no manifold for a wheel more than a wheel
// radius above the ground). Empty on rails.
void vehicle_contacts(const World& world, const VehicleScene& scene,
                      std::vector<ContactManifold>& out);

// The frequency (Hz) and damping ratio of a decaying oscillation about `rest`, from its
// samples every dt: the damped period from upward crossings of rest, the decay from the
// ratio of successive peaks above it (log decrement). Zero when fewer than two periods.
struct Bounce {
  double hertz = 0.0;
  double damping_ratio = 0.0;
};
Bounce measure_bounce(const std::vector<double>& samples, double rest, double dt);

}  // namespace softstep::scenes
