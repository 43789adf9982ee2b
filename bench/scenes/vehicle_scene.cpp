#include "scenes/vehicle_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scenes/sphere_contacts.hpp"

namespace softstep::scenes {

namespace {

BodyId dynamic(World& world, const Eigen::Vector3d& position, double mass,
               const Eigen::Matrix3d& inertia, const Eigen::Vector3d& velocity,
               const Eigen::Vector3d& spin = Eigen::Vector3d::Zero()) {
  BodyDef d;
  d.position = position;
  d.mass = mass;
  d.inertia = inertia;
  d.linear_velocity = velocity;
  d.angular_velocity = spin;
  return world.create_body(d);
}

// The rail: a wheel joint from the world whose free travel is along x (no spring), so the
// wheel rolls along x and spins with its centre at axle height. A rigid row, a 60 Hz spring
// on the wheel's mass (WorldSettings::rigid_hertz) in series with the suspension: it lowers
// the bounce by k_spring / (2 k_rail), 0.8 % for 20 kg wheels.
JointId rail(World& world, BodyId ground, BodyId wheel) {
  const Eigen::Vector3d centre = world.body(wheel).position;
  const JointFrames f = frames_at(world, ground, wheel, centre, Eigen::Vector3d::UnitX(),
                                  Eigen::Vector3d::UnitZ());
  WheelJointDef on_rail;
  on_rail.body_a = ground;
  on_rail.body_b = wheel;
  on_rail.frame_a = f.a;
  on_rail.frame_b = f.b;
  return world.create_joint(on_rail);
}

// build_car, its suspension in N/m when `absolute`.
Car make_car(World& world, const VehicleOptions& o, const Eigen::Vector3d& ground_point,
             bool absolute, std::vector<JointId>& joints) {
  Car car;
  const double r = o.wheel_radius;
  const double axle_height = ground_point.y() + r;
  car.start_height = axle_height + 0.3;  // the chassis centre 0.3 m above the axles, unloaded
  const double start_speed = o.start_rolling ? o.speed : 0.0;
  const Eigen::Vector3d velocity(start_speed, 0.0, 0.0);
  car.chassis = dynamic(world, {ground_point.x(), car.start_height, ground_point.z()},
                        o.chassis_mass, solid_box_inertia(o.chassis_mass, {4.2, 0.6, 1.8}),
                        velocity);
  // A disc about its axle z: m r^2 / 2; about a diameter: m r^2 / 4.
  const Eigen::Matrix3d wheel_inertia =
      Eigen::Vector3d(0.25, 0.25, 0.5).asDiagonal() * (o.wheel_mass * r * r);
  // Rolling along +x with the axle along z: the spin about z is -v / r.
  const double rolling = -o.speed / r;
  for (int k = 0; k < 4; ++k) {
    const double x = (k < 2 ? 0.5 : -0.5) * o.wheelbase;
    const double side = (k % 2 == 0 ? -0.5 : 0.5) * o.track;
    const Eigen::Vector3d centre(ground_point.x() + x, axle_height, ground_point.z() + side);
    car.wheels[k] = dynamic(world, centre, o.wheel_mass, wheel_inertia, velocity,
                            {0, 0, -start_speed / r});
    const JointFrames f = frames_at(world, car.chassis, car.wheels[k], centre,
                                    Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
    WheelJointDef w;
    w.body_a = car.chassis;
    w.body_b = car.wheels[k];
    w.frame_a = f.a;
    w.frame_b = f.b;
    w.spring.spring = Spring::soft(o.hertz, o.damping_ratio);
    w.sprung_mass = o.chassis_mass / 4.0;
    if (absolute) {
      // The same spring in N/m and N s/m (wheel.hpp): k = m_s omega^2, c = 2 m_s zeta omega.
      const double omega = 2.0 * std::numbers::pi * o.hertz;
      w.spring.spring = Spring::absolute(w.sprung_mass * omega * omega,
                                         2.0 * w.sprung_mass * o.damping_ratio * omega);
      w.sprung_mass = 0.0;  // not used by an absolute spring
    }
    w.limit = {true, -0.25, 0.25};
    w.motor = {o.motor_torque > 0.0, rolling, o.motor_torque};
    w.steering = k < 2 ? o.steering : 0.0;
    car.wheel_joints[k] = world.create_joint(w);
    joints.push_back(car.wheel_joints[k]);
  }
  return car;
}

}  // namespace

Car build_car(World& world, const VehicleOptions& o, const Eigen::Vector3d& ground_point,
              std::vector<JointId>& joints) {
  return make_car(world, o, ground_point, false, joints);
}

VehicleScene build_vehicle(World& world, const VehicleOptions& o) {
  VehicleScene s;
  BodyDef g;
  g.type = BodyType::Static;
  s.ground = world.create_body(g);
  s.on_rails = o.on_rails;
  s.wheel_radius = o.wheel_radius;
  s.tyre_friction = o.tyre_friction;
  const double gravity = -world.settings().gravity.y();
  const double omega = 2.0 * std::numbers::pi * o.hertz;
  s.promised_sag = gravity / (omega * omega);
  for (int c = 0; c < o.cars; ++c) {
    const bool absolute = o.absolute_every > 0 && c % o.absolute_every == 0;
    Car car = make_car(world, o, {0.0, 0.0, 4.0 * c}, absolute, s.joints);
    if (o.on_rails) {
      for (int k = 0; k < 4; ++k) {
        car.rails[k] = rail(world, s.ground, car.wheels[k]);
        s.joints.push_back(car.rails[k]);
      }
    }
    s.cars.push_back(car);
  }
  if (!o.on_rails) {
    const double contact_omega = 2.0 * std::numbers::pi * world.settings().contact.hertz;
    s.promised_tyre_compression = (o.chassis_mass / 4.0 + o.wheel_mass) * gravity /
                                  (o.wheel_mass * contact_omega * contact_omega);
  }
  s.promised_ride_height = s.cars.front().start_height - s.promised_sag -
                           s.promised_tyre_compression;
  return s;
}

void vehicle_contacts(const World& world, const VehicleScene& s,
                      std::vector<ContactManifold>& out) {
  out.clear();
  if (s.on_rails) return;
  for (const Car& car : s.cars) {
    for (BodyId wheel : car.wheels) {
      // Within a wheel radius the point is speculative: a car dropped or jumping lands on it.
      if (auto m = sphere_on_plane(world, s.ground, 0.0, {wheel, s.wheel_radius}, s.wheel_radius,
                                   s.tyre_friction))
        out.push_back(*m);
    }
  }
}

Bounce measure_bounce(const std::vector<double>& samples, double rest, double dt) {
  std::vector<double> crossings, peaks;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double a = samples[i - 1] - rest, b = samples[i] - rest;
    if (a < 0.0 && b >= 0.0) crossings.push_back((double(i) - 1.0 + a / (a - b)) * dt);
    // A peak above rest after the first upward crossing, refined by the parabola through
    // the three samples around it.
    if (i + 1 < samples.size() && !crossings.empty() && b > 0.0 && b >= a &&
        b > samples[i + 1] - rest) {
      const double c = samples[i + 1] - rest;
      const double curvature = a - 2.0 * b + c;
      peaks.push_back(curvature < 0.0 ? b - (c - a) * (c - a) / (8.0 * curvature) : b);
    }
  }
  Bounce out;
  if (crossings.size() < 3 || peaks.size() < 2) return out;
  const double period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // Log decrement over the first two peaks above rest (later ones sink into the noise).
  const double delta = std::log(peaks[0] / peaks[1]);
  out.damping_ratio = delta / std::sqrt(4.0 * std::numbers::pi * std::numbers::pi + delta * delta);
  const double damped = 2.0 * std::numbers::pi / period;
  out.hertz =
      damped / std::sqrt(1.0 - out.damping_ratio * out.damping_ratio) / (2.0 * std::numbers::pi);
  return out;
}

}  // namespace softstep::scenes
