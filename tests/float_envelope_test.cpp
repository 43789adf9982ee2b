// Worlds built at the corners of the accepted input ranges (validation.cpp, "the float
// envelope") stay finite: every value at its bound at once, stepped at the largest and the
// smallest sub-step. The fuzzer's first finding was such a world, with values each accepted
// under the earlier bounds, whose products left float in the kernels.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

struct Corner {
  double light_mass, heavy_mass, inertia, anchor, substep;
  Spring spring;
  double rigid_hertz;  // and max_correction_speed
};

std::string describe(const Corner& c) {
  char text[200];
  std::snprintf(text, sizeof text,
                "masses %g / %g kg, inertia %g kg m^2, anchor %g m, sub-step %g s, spring %g Hz "
                "zeta %g, rigid %g Hz",
                c.light_mass, c.heavy_mass, c.inertia, c.anchor, c.substep, c.spring.hertz,
                c.spring.damping_ratio, c.rigid_hertz);
  return text;
}

// A kinematic body at the speed limit drags a light and a heavy body on joints anchored at
// the anchor bound, in gravity at the magnitude bound, from positions at the position bound.
void expect_finite_at(const Corner& c) {
  constexpr double kSpeedLimit = 1e6;  // the largest max_linear_speed
  constexpr double kFar = 1e9;         // positions, anchors, gravity
  World world(WorldSettings{.gravity = {0.0, -kFar, kFar},
                            .substeps = 1,
                            .rigid_hertz = c.rigid_hertz,
                            .max_correction_speed = c.rigid_hertz,
                            .max_linear_speed = kSpeedLimit});
  BodyDef driver;
  driver.type = BodyType::Kinematic;
  driver.position = {-kFar, 0.0, 0.0};
  driver.linear_velocity = {kSpeedLimit, 0.0, 0.0};
  driver.angular_velocity = {kFar, 0.0, 0.0};
  BodyDef light;
  light.position = {kFar, kFar, -kFar};
  light.linear_velocity = {0.0, -kSpeedLimit, 0.0};
  light.mass = c.light_mass;
  light.inertia = Eigen::Matrix3d::Identity() * c.inertia;
  BodyDef heavy = light;
  heavy.position = {0.0, -kFar, kFar};
  heavy.mass = c.heavy_mass;
  heavy.gravity_scale = -1.0;
  const BodyId ids[] = {world.create_body(driver), world.create_body(light),
                        world.create_body(heavy)};
  // A ball joint's point rows reach at most m |r|^2 / I_min = kMaxLeverCondition from a
  // dynamic body's centre (validation::point_lever): a corner beyond it is refused instead.
  constexpr double kMaxLeverCondition = 1e7;
  const double lever_squared = 2.0 * c.anchor * c.anchor;  // both anchors
  for (int j = 0; j < 2; ++j) {
    // Joint 0 holds the light body, joint 1 the light and the heavy one.
    const double mass = j == 0 ? c.light_mass : std::max(c.light_mass, c.heavy_mass);
    const bool beyond_reach = mass * lever_squared / c.inertia > kMaxLeverCondition;
    BallJointDef ball;
    ball.body_a = ids[j];
    ball.body_b = ids[j + 1];
    ball.local_anchor_a = {c.anchor, -c.anchor, 0.0};
    ball.local_anchor_b = {0.0, c.anchor, c.anchor};
    ball.spring = c.spring;
    if (beyond_reach) {
      EXPECT_THROW(world.create_ball_joint(ball), InvalidArgument) << describe(c);
      return;
    }
    world.create_ball_joint(ball);
    DistanceJointDef rope;
    rope.body_a = ids[j];
    rope.body_b = ids[j + 1];
    rope.local_anchor_b = {c.anchor, 0.0, 0.0};
    rope.spring = Spring::free();
    rope.max_length = 1.0;
    world.create_distance_joint(rope);
  }
  for (int step = 0; step < 20; ++step) {
    world.step(c.substep);
    for (BodyId id : ids) {
      const BodyState s = world.body(id);
      ASSERT_TRUE(s.position.allFinite() && s.orientation.coeffs().allFinite() &&
                  s.linear_velocity.allFinite() && s.angular_velocity.allFinite())
          << describe(c) << ", step " << step;
      if (s.type == BodyType::Dynamic) {
        // The bound holds where velocities are integrated and where positions move; the
        // relax pass after it may add the constraints' pull, which here is at most a joint's
        // correction of the bodies' own separation per sub-step.
        EXPECT_LE(s.linear_velocity.norm(), 1e3 * kSpeedLimit + 10.0 * kFar / c.substep)
            << describe(c);
      }
    }
  }
}

TEST(FloatEnvelope, CornersOfTheAcceptedRangesStayFinite) {
  for (double light : {1e-9, 1.0})
    for (double heavy : {1.0, 1e15})
      for (double inertia : {1e-15, 1e24})
        for (double anchor : {0.0, 1e9})
          for (double substep : {1e-9, 1e3})
            for (Spring spring : {Spring::rigid(), Spring::soft(1e9, 0.0), Spring::soft(1e-6, 0.0),
                                  Spring::soft(1e-6, 1e9)})
              for (double rigid_hertz : {1e-6, 1e9})
                expect_finite_at({light, heavy, inertia, anchor, substep, spring, rigid_hertz});
}

// Gravity cannot push a body past the speed limit: the clamp holds it there, in any direction.
TEST(FloatEnvelope, SpeedIsClampedToTheLimit) {
  World world(WorldSettings{.gravity = {3e3, -4e3, 0.0}, .max_linear_speed = 100.0});
  const BodyId body = world.create_body(BodyDef{});
  for (int step = 0; step < 30; ++step) world.step(1.0 / 60.0);
  const Eigen::Vector3d v = world.body(body).linear_velocity;
  EXPECT_NEAR(v.norm(), 100.0, 1e-4);
  EXPECT_NEAR(v.x() / v.norm(), 0.6, 1e-6);  // the direction of the pull is kept
  EXPECT_NEAR(v.y() / v.norm(), -0.8, 1e-6);
}

// Beyond ~1.8e19 m/s a speed's square leaves float: the clamp must still slow the body along
// its direction (it set it to 0 before). Gravity at its bounds for one 1e3 s sub-step gives
// 1e21 m/s.
TEST(FloatEnvelope, SpeedWhoseSquareOverflowsIsClampedAlongItsDirection) {
  World world(WorldSettings{.gravity = {6e8, -8e8, 0.0}, .substeps = 1, .max_linear_speed = 100.0});
  BodyDef d;
  d.gravity_scale = 1e9;
  const BodyId body = world.create_body(d);
  world.step(1e3);
  const Eigen::Vector3d v = world.body(body).linear_velocity;
  EXPECT_NEAR(v.norm(), 100.0, 1e-4);
  EXPECT_NEAR(v.x() / v.norm(), 0.6, 1e-6);
  EXPECT_NEAR(v.y() / v.norm(), -0.8, 1e-6);
}

// An undamped rigid row (rigid_damping_ratio 0, accepted) at the lowest rigid_hertz has
// a = (h omega)^2 ~ 7e-16 and a feedback 1/a ~ 1.5e15; against a body of the largest inertia
// (1e24 kg m^2) the prismatic's angular lock multiplied it past float (7e38) and both bodies
// were NaN after one step. make_context caps the rigid and limit feedback at 1e13, where the
// row's mass_scale a / (1 + a) is below 1e-13 and it applies nothing anyway.
TEST(FloatEnvelope, UndampedRigidRowsAtTheLowestFrequencyStayFinite) {
  for (double substep : {1.0 / 240.0, 1e-9}) {
    World world(WorldSettings{.gravity = {0.0, 0.0, 0.0},
                              .substeps = 1,
                              .rigid_hertz = substep < 1e-6 ? 5.0 : 1e-6,
                              .rigid_damping_ratio = 0.0});
    BodyDef d;
    d.inertia = Eigen::Matrix3d::Identity() * 1e24;
    const BodyId a = world.create_body(d);
    d.angular_velocity = {0.0, 0.0, 1.0};
    const BodyId b = world.create_body(d);
    PrismaticJointDef slider;
    slider.body_a = a;
    slider.body_b = b;
    world.create_joint(slider);
    for (int step = 0; step < 60; ++step) {
      world.step(substep);
      for (BodyId id : {a, b}) {
        const BodyState s = world.body(id);
        ASSERT_TRUE(s.position.allFinite() && s.orientation.coeffs().allFinite() &&
                    s.linear_velocity.allFinite() && s.angular_velocity.allFinite())
            << "sub-step " << substep << " s, step " << step;
      }
    }
  }
}

// The slowest rigid rows (rigid_hertz 1e-6, accepted, the default damping ratio 2) are
// springs that barely pull: a 1 kg body whose ball joint was created 1 m open, solved four
// times per sub-step without a relax pass, falls as if free for its first second (the row's
// bias asks omega / (2 zeta) * 1 m = 1.6e-6 m/s of it). With mass_scale computed as
// 1 - 1/(1 + a) in float (a = 1.05e-7) each solve gave back 14 % more impulse than it held
// (Spring.KernelSoftnessGivesBackLessThanItHoldsAtEveryFrequency): the impulse carrying the
// body's weight grew until the body was NaN at step 59 (a corner sampler's world).
TEST(FloatEnvelope, SlowestRigidRowsDoNotGrowTheirImpulse) {
  const WorldSettings settings{.solve_iterations = 4, .relax_iterations = 0, .rigid_hertz = 1e-6};
  World world(settings);
  const BodyId anchor = world.create_body(BodyDef{.type = BodyType::Static});
  BodyDef d;
  d.position = {1.0, 0.0, 0.0};
  const BodyId body = world.create_body(d);
  BallJointDef ball;
  ball.body_a = anchor;
  ball.body_b = body;
  world.create_ball_joint(ball);
  double fastest = 0.0;
  for (int step = 0; step < 60; ++step) {
    world.step(1.0 / 60.0);
    const BodyState s = world.body(body);
    ASSERT_TRUE(s.position.allFinite() && s.linear_velocity.allFinite()) << "step " << step;
    fastest = std::max(fastest, s.linear_velocity.norm());
  }
  EXPECT_LT(fastest, 1.01 * settings.gravity.norm() * 1.0);  // a second of free fall
}

// A revolute or a wheel created with its axles crossed, exactly 90 degrees apart: the hinge
// lock's row for that lean has a Jacobian of float rounding and an error of 1 rad. Asked to
// close it at max_correction_speed, the row divided by its rounding: the unit body went NaN
// at step 50, the wheel's body of the largest inertia at step 0 (K^-1 (J v + bias) left
// float). The row's correction is bounded by its length now (angular_parts.hpp).
TEST(FloatEnvelope, HingeLocksCreatedWithCrossedAxesStayFinite) {
  for (double inertia : {1.0, 1e24}) {
    for (bool wheel : {false, true}) {
      World world;
      const BodyId ground = world.create_body(BodyDef{.type = BodyType::Static});
      BodyDef d;
      d.position = {2.0, 0.0, 0.0};
      d.inertia = Eigen::Matrix3d::Identity() * inertia;
      const BodyId body = world.create_body(d);
      const JointFrame along_y{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                               Eigen::Vector3d::UnitY()};
      const JointFrame along_x{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                               Eigen::Vector3d::UnitX()};
      if (wheel) {  // the axles are the references
        WheelJointDef j;
        j.body_a = ground;
        j.body_b = body;
        j.frame_a = along_y;
        j.frame_b = along_x;
        j.sprung_mass = 1.0;
        world.create_joint(j);
      } else {  // the hinge axes are the axes
        RevoluteJointDef j;
        j.body_a = ground;
        j.body_b = body;
        j.frame_a = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
        j.frame_b = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
        world.create_joint(j);
      }
      for (int step = 0; step < 60; ++step) {
        world.step(1.0 / 60.0);
        const BodyState s = world.body(body);
        ASSERT_TRUE(s.position.allFinite() && s.orientation.coeffs().allFinite() &&
                    s.linear_velocity.allFinite() && s.angular_velocity.allFinite())
            << (wheel ? "wheel" : "revolute") << ", inertia " << inertia << ", step " << step;
      }
    }
  }
}

// Rows that cannot all hold, softened to rigid_hertz 0.5 so that the warm start carries
// large impulses from one sub-step to the next: a 0.5 kg, 0.05 kg m^2 body held by a rigid
// ball joint to a kinematic body at the origin, its anchor 70 m from its centre, and joined
// to a second kinematic body by `fight`. The fuzzer's two worlds of this shape grew the
// body's speed ~10x a step to NaN while the speed limit (0.5 m/s) bound only as velocities
// were integrated: the solve pushed it to 3e11 m/s and positions moved at that speed. The
// limits now bind again where positions move, so the body moves at most max_linear_speed dt
// per step, whatever the relax pass reports as its velocity.
template <class Def>
void expect_moves_within_the_speed_limit(const char* name, Def fight,
                                         const Eigen::Vector3d& driver_spin) {
  constexpr double kLimit = 0.5;
  World world(
      WorldSettings{.gravity = {0.5, 0.5, 0.5}, .rigid_hertz = 0.5, .max_linear_speed = kLimit});
  BodyDef held;
  held.position = {74.27, -7.92, -0.72};
  held.orientation = Quaternion(0.214, 0.0, -0.977, -0.006).normalized();
  held.mass = 0.5;
  held.inertia = Eigen::Matrix3d::Identity() * 0.05;
  held.gravity_scale = -98.4;
  BodyDef pin;
  pin.type = BodyType::Kinematic;
  BodyDef driver = pin;
  driver.position = {-100.0, 0.0, 0.0};
  driver.angular_velocity = driver_spin;
  const BodyId body = world.create_body(held);
  const BodyId origin = world.create_body(pin);
  BallJointDef ball;
  ball.body_a = origin;
  ball.body_b = body;
  ball.local_anchor_b = {0.0, -53.36, 46.88};
  world.create_ball_joint(ball);
  fight.body_a = body;
  fight.body_b = world.create_body(driver);
  world.create_joint(fight);
  const double dt = 1.0 / 60.0;
  for (int step = 0; step < 300; ++step) {
    const Eigen::Vector3d before = world.body(body).position;
    world.step(dt);
    const BodyState s = world.body(body);
    ASSERT_TRUE(s.position.allFinite() && s.linear_velocity.allFinite() &&
                s.angular_velocity.allFinite())
        << name << ", step " << step;
    ASSERT_LE((s.position - before).norm(), kLimit * dt * (1.0 + 1e-5))
        << name << ", step " << step;
  }
}

TEST(FloatEnvelope, RowsThatCannotHoldMoveABodyNoFasterThanTheLimit) {
  // A prismatic whose 1e6 N motor drives towards a limit 1e6 m out along a tilted axis.
  PrismaticJointDef slider;
  slider.frame_a = {{0.0, 0.0, 0.0}, {48.15, 1e6, 1e6}, {0.0, 1.0, 0.0}};
  slider.frame_b = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  slider.limit = {true, 1e6, 1e6};
  slider.motor = {true, 1e6, 1e6};
  expect_moves_within_the_speed_limit("prismatic motor against a ball", slider,
                                      Eigen::Vector3d::Zero());
  // A revolute whose anchor sits 173 m from a kinematic body that spins at the spin limit,
  // dragging it round at ~30 km/s.
  RevoluteJointDef hinge;
  hinge.frame_a = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}};
  hinge.frame_b = {{-100.0, -100.0, -100.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  hinge.motor = {true, 0.5, 0.5};
  expect_moves_within_the_speed_limit("revolute to a whirling kinematic body", hinge,
                                      {0.0, 0.0, 1000.0});
}

}  // namespace
}  // namespace softstep
