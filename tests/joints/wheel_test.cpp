// The wheel joint keeps the promises of wheel.hpp: a car bounces at its springs' frequency
// and damping ratio whatever its wheels weigh, its motor spins a wheel up no faster than its
// torque allows, and steering turns the axle by the angle set.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <ostream>

#include "joints/joint_test_support.hpp"
#include "scenes/vehicle_scene.hpp"

namespace softstep {
namespace {

using test::kDt;

struct Suspension {
  double wheel_mass;  // kg
  bool absolute;      // the springs as Spring::absolute(k, c) in N/m (vehicle_scene.hpp)
};
void PrintTo(const Suspension& s, std::ostream* os) {
  *os << s.wheel_mass << " kg wheels" << (s.absolute ? ", N/m" : "");
}

class CarBounce : public ::testing::TestWithParam<Suspension> {};

// A 1,200 kg car on four 2 Hz, 0.3 damping-ratio springs, its wheels held on rails at axle
// height, released with its springs unloaded: its heave is a damped oscillator of
// M z'' = -4 k z - 4 c z' with k = (M/4) omega^2 and c = 2 (M/4) zeta omega, so it bounces at
// 2 Hz with ratio 0.3 about g / omega^2 below its start. With 60 Hz steps and 4 sub-steps
// the soft step's own error (implicit Euler, with its numerical damping given back, see
// wheel_joint_kernel.hpp) is under 1 % in both, and the rails' compliance (vehicle_scene.hpp)
// lowers the frequency by at most 0.8 % (20 kg wheels); the bound is 3 %. A spring relative
// to the row's own mass (dominated by the wheel) would bounce at about 2 Hz sqrt(m_wheel /
// 300 kg), 0.5 Hz. The same springs in N/m (Spring::absolute(k, c), tuned for the chassis
// not the wheel) must carry the chassis at the same m_s g / k and bounce the same.
TEST_P(CarBounce, AtTheSpringsFrequencyAndDampingRatioWhateverTheWheelsWeigh) {
  scenes::VehicleOptions o;
  o.wheel_mass = GetParam().wheel_mass;
  o.absolute_every = GetParam().absolute ? 1 : 0;
  o.on_rails = true;  // the joint's promise, without the tyres' compliance in series
  o.speed = 0.0;
  o.motor_torque = 0.0;
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  const scenes::VehicleScene scene = scenes::build_vehicle(world, o);
  const scenes::Car& car = scene.cars[0];
  std::vector<double> heights{world.body(car.chassis).position.y()};
  for (int i = 0; i < 450; ++i) {
    world.step(kDt);
    heights.push_back(world.body(car.chassis).position.y());
  }
  // The spring's travel at rest is its static deflection m_s g / k (m_s = M / 4; g / omega^2
  // for the relative spring): the soft step has no error at equilibrium (its impulse is then
  // the static force exactly). k from the joint's own spring (Spring::stiffness: m_s omega^2
  // or the absolute k). The chassis rests where it settled (the rails' own sag, about 1 mm,
  // lies below it).
  const WheelJointDef def = world.joint_def<WheelJointDef>(car.wheel_joints[0]);
  ASSERT_EQ(def.spring.spring.is_absolute(), GetParam().absolute);
  const double sprung = o.chassis_mass / 4.0;
  const double k = def.spring.spring.stiffness(sprung);
  EXPECT_NEAR(world.joint_reading(car.wheel_joints[0]).position, sprung * 9.81 / k, 1e-5);
  EXPECT_NEAR(scene.promised_sag, sprung * 9.81 / k, 1e-9);
  const double rest = heights.back();
  // 2.5 s: five periods, the amplitude falls from 0.06 m to 1e-5 m.
  heights.resize(151);
  const scenes::Bounce b = scenes::measure_bounce(heights, rest, kDt);
  EXPECT_NEAR(b.hertz, o.hertz, 0.03 * o.hertz);
  EXPECT_NEAR(b.damping_ratio, o.damping_ratio, 0.03 * o.damping_ratio);
}

INSTANTIATE_TEST_SUITE_P(WheelMasses, CarBounce,
                         ::testing::Values(Suspension{10.0, false}, Suspension{20.0, false},
                                           Suspension{40.0, false}, Suspension{10.0, true},
                                           Suspension{40.0, true}));

struct LoneWheel {
  World world;
  BodyId chassis, wheel;
  JointId joint;
  WheelJointDef def;
  double inertia;  // about the axle, kg m^2
};

// A 20 kg wheel of radius 0.35 m (a disc) on a static chassis, no gravity, axle along z.
std::unique_ptr<LoneWheel> lone_wheel(const AngularMotor& motor) {
  WorldSettings settings;
  settings.gravity = Eigen::Vector3d::Zero();
  settings.sleeping = false;
  auto w = std::make_unique<LoneWheel>(LoneWheel{World(settings), {}, {}, {}, {}, 0.0});
  w->chassis = test::static_body(w->world, {0.0, 1.0, 0.0});
  const double m = 20.0, r = 0.35;
  w->inertia = 0.5 * m * r * r;
  w->wheel = test::dynamic_body(w->world, {1.0, 0.5, 0.8}, m,
                                Eigen::Vector3d(0.25, 0.25, 0.5).asDiagonal() * (m * r * r));
  const JointFrames f = frames_at(w->world, w->chassis, w->wheel, {1.0, 0.5, 0.8},
                                  Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
  w->def.body_a = w->chassis;
  w->def.body_b = w->wheel;
  w->def.frame_a = f.a;
  w->def.frame_b = f.b;
  w->def.spring.spring = Spring::soft(3.0, 0.5);
  w->def.sprung_mass = 300.0;
  w->def.motor = motor;
  w->joint = w->world.create_joint(w->def);
  return w;
}

// The motor's torque is capped at tau, so the spin grows at most tau / I per second: it
// reaches the target speed omega no sooner than t* = omega I / tau, and (the cap binding all
// the way, nothing else turning the wheel) exactly then. Checked every step: never faster
// than tau t / I (+ float noise), within 1 % of it while accelerating, at the target after.
TEST(WheelMotor, ReachesItsSpeedAtTheRateItsMaxTorqueAllows) {
  const double target = 20.0, tau = 10.0;
  auto w = lone_wheel({true, target, tau});
  const double rate = tau / w->inertia;          // rad/s^2
  const double reach_time = target / rate;       // 2.45 s
  for (int i = 1; i <= 240; ++i) {
    w->world.step(kDt);
    const double t = i * kDt;
    const double spin = w->world.body(w->wheel).angular_velocity.z();
    EXPECT_LE(spin, rate * t * (1.0 + 1e-5) + 1e-6) << "at " << t << " s";
    if (t < 0.98 * reach_time) {
      EXPECT_NEAR(spin, rate * t, 0.01 * rate * t) << "at " << t << " s";
    }
    if (t > reach_time + 0.05) {
      EXPECT_NEAR(spin, target, 1e-3 * target) << "at " << t << " s";
    }
  }
  // The reading's motor impulse is the torque of the last sub-step: at speed, none is needed.
  EXPECT_NEAR(w->world.joint_reading(w->joint).motor_impulse, 0.0, 1e-3);
}

// Steering set at run time through set_joint turns the axle about the suspension axis by the
// angle (the rigid axle rows: within 1e-3 rad after a second), the wheel still spinning about
// the turned axle.
TEST(WheelSteering, TurnsTheAxleByTheSetAngle) {
  auto w = lone_wheel({});
  w->world.set_angular_velocity(w->wheel, {0.0, 0.0, 5.0});
  for (int i = 0; i < 10; ++i) w->world.step(kDt);
  const std::uint64_t colors_before = w->world.solver_layout().colors_used;
  for (double angle : {0.3, -0.5}) {
    w->def.steering = angle;
    w->world.set_joint(w->joint, w->def);
    for (int i = 0; i < 60; ++i) w->world.step(kDt);
    const Eigen::Vector3d axle =
        w->world.body(w->wheel).orientation * w->def.frame_b.local_reference;
    const Eigen::Vector3d wanted =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitZ();
    EXPECT_LT(std::acos(std::min(1.0, axle.dot(wanted))), 1e-3) << "steering " << angle;
    EXPECT_LT(w->world.joint_reading(w->joint).angular_error, 1e-3);
    // The wheel still spins, about the turned axle only (the axle rows took the rest).
    const Eigen::Vector3d spin = w->world.body(w->wheel).angular_velocity;
    EXPECT_GT(spin.dot(wanted), 1.0);
    EXPECT_LT((spin - spin.dot(wanted) * wanted).norm(), 1e-3);
  }
  EXPECT_EQ(w->world.solver_layout().colors_used, colors_before);
  EXPECT_EQ(w->world.joint_def<WheelJointDef>(w->joint).steering, -0.5);
}

// The smallest sprung mass a soft spring accepts (1e-9 kg, a body's smallest mass), at the
// softest and stiffest frequencies and at the smallest, a game's and the largest sub-step,
// the wheel bounced along its suspension: every state stays finite. (Positive masses below
// it were accepted before, and 1e-40 kg turned the bodies to NaN in the first step: the float
// spring's 1 / (h (h k + c)) overflowed.)
TEST(WheelJoint, SmallestSprungMassStaysFinite) {
  for (const double hertz : {1e-6, 2.0, 1e9}) {
    for (const double dt : {4e-9, kDt, 4e3}) {
      auto w = lone_wheel({});
      w->def.sprung_mass = 1e-9;
      w->def.spring.spring = Spring::soft(hertz, 0.0);
      w->world.set_joint(w->joint, w->def);
      w->world.set_linear_velocity(w->wheel, {0.0, 1.0, 0.0});
      for (int i = 0; i < 20; ++i) {
        w->world.step(dt);
        const BodyState b = w->world.body(w->wheel);
        ASSERT_TRUE(b.position.allFinite() && b.linear_velocity.allFinite() &&
                    b.angular_velocity.allFinite())
            << hertz << " Hz, dt " << dt << " s, step " << i;
      }
    }
  }
}

// The Def comes back as stored (axes normalized), through create_joint and joint_def.
TEST(WheelJoint, JointDefRoundTrips) {
  auto w = lone_wheel({true, 3.0, 7.0});
  const WheelJointDef got = w->world.joint_def<WheelJointDef>(w->joint);
  EXPECT_EQ(got.sprung_mass, 300.0);
  EXPECT_EQ(got.motor.max_torque, 7.0);
  EXPECT_EQ(got.spring.spring.hertz, 3.0);
  EXPECT_EQ(w->world.joint_type(w->joint), JointType::Wheel);
  EXPECT_STREQ(joint_type_name(JointType::Wheel), "wheel");
}

}  // namespace
}  // namespace softstep
