// The prismatic joint keeps the promises of prismatic.hpp: B slides only along A's axis and
// keeps its orientation, its translation stays within the limits, and its motor drives at
// most its force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "frame_constants.hpp"
#include "joints/joint_test_support.hpp"
#include "scenes/joint_at.hpp"

namespace softstep {
namespace {

using test::kDt;
using test::kG;

// The rigid row's bounds: test::rigid_row_bound (joint_test_support.hpp).
using test::kOmegaRigid;
using test::rigid_row_bound;

struct Slider {
  World world;
  BodyId ground, body;
  JointId joint;
  PrismaticJointDef def;
  Eigen::Vector3d axis;  // world
};

// A 2 kg box on a slider along `axis` (world) through its point `anchor_offset` from its
// centre (body frame), from a static ground, under gravity.
Slider make_slider(const Eigen::Vector3d& axis, const Eigen::Vector3d& anchor_offset,
                   const AxisLimit& limit = {}, const LinearMotor& motor = {}) {
  WorldSettings settings;
  settings.sleeping = false;  // the limit readings are read while the body rests on a limit
  Slider s{World(settings), {}, {}, {}, {}, axis.normalized()};
  s.ground = test::static_body(s.world);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  s.body = test::dynamic_body(s.world, {0.0, 1.0, 0.0}, 2.0,
                              test::turned(solid_box_inertia(2.0, {0.4, 0.2, 0.3}), turn));
  s.def = scenes::joint_at<PrismaticJointDef>(
      s.world, s.ground, s.body, Eigen::Vector3d(0.0, 1.0, 0.0) + anchor_offset, s.axis);
  s.def.limit = limit;
  s.def.motor = motor;
  s.joint = s.world.create_joint(s.def);
  return s;
}

// Anchored off the centre, the perpendicular rows push at the anchor and so turn the body
// unless the angular rows hold it; the inertia is turned off the axes as well.
TEST(Prismatic, SlidesOnlyAlongItsTiltedAxisAcceleratingAtGravityAlongIt) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  Slider s = make_slider(axis, {0.2, 0.1, -0.15});
  const Eigen::Vector3d g(0.0, -kG, 0.0);
  const double along = g.dot(s.axis);  // m/s^2
  const double g_perp = (g - along * s.axis).norm();
  const Eigen::Vector3d start = s.world.body(s.body).position;
  const int substeps = s.world.settings().substeps;
  const double h = kDt / substeps;
  double worst_gap = 0.0, worst_turn = 0.0, worst_spin = 0.0;
  const int steps = 60;
  for (int i = 0; i < steps; ++i) {
    s.world.step(kDt);
    const JointReading r = s.world.joint_reading(s.joint);
    worst_gap = std::max(worst_gap, r.error);
    worst_turn = std::max(worst_turn, r.angular_error);
    worst_spin = std::max(worst_spin, s.world.body(s.body).angular_velocity.norm());
  }
  // Semi-implicit Euler under a constant acceleration a: after n sub-steps v = a n h and
  // x = a h^2 n (n + 1) / 2. The rows remove g_perp h of perpendicular velocity per sub-step;
  // what they leave is their sag, so the motion along the axis is exact to 1e-4.
  const int n = steps * substeps;
  const BodyState b = s.world.body(s.body);
  const double v_along = b.linear_velocity.dot(s.axis);
  EXPECT_NEAR(v_along, along * n * h, 1e-4 * along * n * h);
  const double x_expected = along * h * h * n * (n + 1) / 2.0;
  EXPECT_NEAR((b.position - start).dot(s.axis), x_expected, 1e-4 * x_expected);
  // The translation is measured at the anchors: turned by the angular rows' sag, the anchor
  // moves along the axis by at most r times that angle.
  EXPECT_NEAR(s.world.joint_reading(s.joint).position, (b.position - start).dot(s.axis),
              0.27 * worst_turn + 1e-6);
  // Perpendicular: no speed (a thousandth of the speed along), and no more distance from the
  // axis than the perpendicular rows' sag carrying m g_perp. Anchored r = 0.27 m off the
  // centre, a row's effective mass is as low as 1 / (1/m + r^2 / I_min) = 0.26 kg.
  const double r = 0.27, i_min = 0.0217, m = 2.0;  // m, kg m^2 (smallest principal), kg
  const double m_eff = 1.0 / (1.0 / m + r * r / i_min);
  EXPECT_LT((b.linear_velocity - v_along * s.axis).norm(), 1e-3 * std::abs(v_along));
  EXPECT_LT(worst_gap, rigid_row_bound(m * g_perp / m_eff, h));
  // Orientation held: the angular rows carry the torque m g_perp r on at least I_min.
  EXPECT_LT(worst_turn, rigid_row_bound(m * g_perp * r / i_min, h));
  // What the rows leave of the body's spin after the relax pass: a hundredth of what one
  // sub-step of that torque would add (m g_perp r h / I_min = 0.5 rad/s).
  EXPECT_LT(worst_spin, 0.01 * m * g_perp * r * h / i_min);
}

// Falls along a steep axis onto the lower limit (-0.5 m), then a motor (3 m |g.a|, 2 m/s)
// pushes it up against the upper limit (+0.3 m). Anchored at the centre, each limit row sees
// the body's mass: the pressing accelerations are |g.a| and 2 |g.a|.
TEST(Prismatic, TranslationStaysWithinItsLimits) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, 0.0).normalized();
  Slider s = make_slider(axis, Eigen::Vector3d::Zero(), {true, -0.5, 0.3});
  const double a = kG * axis.y();
  const double h = kDt / s.world.settings().substeps;
  double lowest = 0.0;
  for (int i = 0; i < 90; ++i) {
    s.world.step(kDt);
    lowest = std::min(lowest, s.world.joint_reading(s.joint).position);
  }
  EXPECT_LT(lowest, -0.5 + 1e-3) << "never reached the lower limit";
  EXPECT_GT(lowest, -0.5 - rigid_row_bound(a, h));
  EXPECT_GT(s.world.joint_reading(s.joint).limit_impulse, 0.0) << "lower pushes up";

  PrismaticJointDef up = s.def;
  up.motor = {true, 2.0, 3.0 * 2.0 * a};
  s.world.set_joint(s.joint, up);
  double highest = -1.0;
  for (int i = 0; i < 90; ++i) {
    s.world.step(kDt);
    highest = std::max(highest, s.world.joint_reading(s.joint).position);
  }
  EXPECT_GT(highest, 0.3 - 1e-3) << "never reached the upper limit";
  EXPECT_LT(highest, 0.3 + rigid_row_bound(2.0 * a, h));
  EXPECT_LT(s.world.joint_reading(s.joint).limit_impulse, 0.0) << "upper pushes down";
}

// A vertical slider's motor lifts the 2 kg box against gravity with at most 2 m g: it
// accelerates at g (at most) to 1 m/s and holds it; no sub-step's impulse exceeds F h.
TEST(Prismatic, MotorReachesItsSpeedAndNeverExceedsItsForce) {
  const double force = 2.0 * 2.0 * kG, speed = 1.0;
  Slider s =
      make_slider(Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero(), {}, {true, speed, force});
  const double h = kDt / s.world.settings().substeps;
  double worst = 0.0;
  for (int i = 1; i <= 30; ++i) {
    s.world.step(kDt);
    const double v = s.world.body(s.body).linear_velocity.y();
    ASSERT_LE(v, (force / 2.0 - kG) * i * kDt * (1.0 + 1e-5) + 1e-6) << "step " << i;
    worst = std::max(worst, std::abs(s.world.joint_reading(s.joint).motor_impulse));
  }
  EXPECT_NEAR(s.world.body(s.body).linear_velocity.y(), speed, 1e-3 * speed);
  EXPECT_LE(worst, force * h * (1.0 + 1e-6));
  EXPECT_GE(worst, force * h * (1.0 - 1e-3)) << "the motor never used its force";
  // Holding the speed, the motor carries the weight: m g h per sub-step.
  EXPECT_NEAR(s.world.joint_reading(s.joint).motor_impulse, 2.0 * kG * h, 1e-3 * 2.0 * kG * h);
}

// The slider's body as A, the static ground as B: a 1 kN motor drives a 0.5 kg, 0.05 kg m^2
// body out along its own axis with the rigid rows soft (rigid_hertz 0.5). The motor's force
// acts on A at B's anchor, further out every step, and turns A about it like a spring of
// sqrt(F d / I) that the sub-step cannot follow: the geometric inertia must take A's lever to
// B's anchor (its own anchor, at its centre, gives none). Without it the solve spins A up
// each sub-step and the speed limits where positions move (body_integration.hpp) are all
// that hold it; before those, the fuzzer's 1e6 N motor grew the body's speed 10x a step to
// NaN. With it A stays still to float rounding: its spin is a millionth of the one without.
TEST(Prismatic, MotorFarAlongALightBodysAxisNeedsTheGeometricInertia) {
  const auto largest_spin = [](bool geometric_stiffness) {
    WorldSettings settings;
    settings.gravity.setZero();
    settings.rigid_hertz = 0.5;
    settings.geometric_stiffness = geometric_stiffness;
    World world(settings);
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, 2.0).normalized();
    const BodyId ground = test::static_body(world);
    const BodyId body = test::dynamic_body(world, axis, 0.5, Eigen::Matrix3d::Identity() * 0.05);
    PrismaticJointDef d =
        scenes::joint_at<PrismaticJointDef>(world, body, ground, Eigen::Vector3d::Zero(), axis);
    d.frame_a.local_anchor.setZero();  // A's anchor at its centre, 1 m from B's
    d.motor = {true, 1e6, 1e3};
    world.create_joint(d);
    double largest = 0.0;
    for (int i = 0; i < 120; ++i) {
      world.step(kDt);
      const double spin = world.body(body).angular_velocity.norm();
      if (!std::isfinite(spin)) return spin;
      largest = std::max(largest, spin);
    }
    return largest;
  };
  const double with = largest_spin(true), without = largest_spin(false);
  EXPECT_LT(with, 1e-9);
  EXPECT_LT(with, 1e-6 * without) << "without the geometric inertia A spins as little";
}

TEST(Prismatic, JointDefRoundTrips) {
  World world;
  const BodyId a = test::static_body(world);
  const BodyId b = test::dynamic_body(world, {1, 0, 0}, 2.0, Eigen::Matrix3d::Identity() * 0.02);
  PrismaticJointDef j;
  j.body_a = a;
  j.body_b = b;
  j.frame_a = {{0.5, 0.1, 0.0}, {2.0, 0.0, 0.0}, {0.0, 0.0, 3.0}};
  j.frame_b = {{-0.5, 0.1, 0.0}, {0.0, -5.0, 0.0}, {0.5, 0.0, 0.0}};
  j.limit = {true, -0.25, 0.5};
  j.motor = {true, 0.75, 12.0};
  j.spring = {Spring::soft(4.0, 0.5), -0.125};
  const PrismaticJointDef got = world.joint_def<PrismaticJointDef>(world.create_joint(j));
  EXPECT_EQ(got.body_a, a);
  EXPECT_EQ(got.body_b, b);
  EXPECT_EQ(got.frame_a.local_anchor, j.frame_a.local_anchor);
  EXPECT_EQ(got.frame_b.local_anchor, j.frame_b.local_anchor);
  EXPECT_TRUE(got.frame_a.local_axis.isApprox(Eigen::Vector3d::UnitX(), 1e-15));
  EXPECT_TRUE(got.frame_b.local_axis.isApprox(-Eigen::Vector3d::UnitY(), 1e-15));
  EXPECT_TRUE(got.frame_a.local_reference.isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  EXPECT_TRUE(got.frame_b.local_reference.isApprox(Eigen::Vector3d::UnitX(), 1e-15));
  EXPECT_EQ(got.limit.lower, -0.25);
  EXPECT_EQ(got.limit.upper, 0.5);
  EXPECT_EQ(got.motor.speed, 0.75);
  EXPECT_EQ(got.motor.max_force, 12.0);
  EXPECT_EQ(got.spring.spring.hertz, 4.0);
  EXPECT_EQ(got.spring.target, -0.125);
}

// A spring's target changed in place moves where the body rests, and wakes it.
TEST(Prismatic, SetJointMovesTheSpringTargetAndWakes) {
  WorldSettings settings;
  settings.gravity.setZero();
  World world(settings);
  const BodyId ground = test::static_body(world);
  const BodyId body = test::dynamic_body(world, {0, 0, 0}, 1.0, Eigen::Matrix3d::Identity() * 0.01);
  auto j = scenes::joint_at<PrismaticJointDef>(world, ground, body, Eigen::Vector3d::Zero(),
                                               Eigen::Vector3d::UnitX());
  j.spring = {Spring::soft(3.0, 1.0), 0.0};
  const JointId id = world.create_joint(j);
  for (int i = 0; i < 60; ++i) world.step(kDt);
  ASSERT_FALSE(world.is_awake(body));
  j.spring.target = 0.4;
  world.set_joint(id, j);
  EXPECT_TRUE(world.is_awake(body));
  for (int i = 0; i < 120; ++i) world.step(kDt);  // critically damped 3 Hz: settled in 2 s
  EXPECT_NEAR(world.joint_reading(id).position, 0.4, 1e-3);
  EXPECT_NEAR(world.body(body).position.x(), 0.4, 1e-3);
}

}  // namespace
}  // namespace softstep
