// apply_force / apply_torque (issue 17, hook 9): kept for the next step, applied in each of
// its sub-steps, then cleared; paid for only while some body has one; bit-identical across
// widths; bad input rejected with the world unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>

#include "expect_invalid_argument.hpp"
#include "frame_constants.hpp"
#include "simd_widths.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

using test::kDt;

WorldSettings weightless(SimdWidth width = SimdWidth::Best) {
  WorldSettings s;
  s.gravity.setZero();
  s.simd = width;
  return s;
}

bool has_stage(const StepPlan& plan, PlanStage stage) {
  return plan.runs(stage);
}

TEST(AppliedForces, ActForOneStepAndAreThenCleared) {
  World world(weightless());
  BodyDef def;
  def.mass = 2.0;
  def.inertia = solid_sphere_inertia(2.0, 0.5);  // 0.2 kg m^2
  const BodyId body = world.create_body(def);
  world.apply_force(body, {4.0, 0.0, 0.0}, def.position);  // at the centre: no torque
  world.apply_force(body, {2.0, 0.0, 0.0}, def.position);  // adds up: 6 N
  world.apply_torque(body, {0.0, 0.0, 0.1});
  world.step(kDt);
  const BodyState after = world.body(body);
  EXPECT_NEAR(after.linear_velocity.x(), 6.0 / 2.0 * kDt, 1e-6);   // F / m dt
  EXPECT_NEAR(after.angular_velocity.z(), 0.1 / 0.2 * kDt, 1e-6);  // tau / I dt
  // Semi-implicit Euler over 4 sub-steps: x = a h^2 (1 + 2 + 3 + 4).
  EXPECT_NEAR(after.position.x(), 3.0 * (kDt / 4) * (kDt / 4) * 10.0, 1e-7);
  world.step(kDt);  // cleared: no more acceleration
  EXPECT_EQ(world.body(body).linear_velocity, after.linear_velocity);
  EXPECT_EQ(world.body(body).angular_velocity, after.angular_velocity);
}

// A force off the centre is that force at the centre plus the torque r x F.
TEST(AppliedForces, ForceAtAPointIsForceAndTorqueAtTheCentre) {
  const auto run = [](bool split) {
    World world(weightless());
    BodyDef def;
    def.position = {1.0, 2.0, 3.0};
    const BodyId body = world.create_body(def);
    const Eigen::Vector3d force(0.0, 3.0, 1.0), arm(0.5, 0.0, 0.0);
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d centre = world.body(body).position;
      if (split) {
        world.apply_force(body, force, centre);
        world.apply_torque(body, arm.cross(force));
      } else {
        world.apply_force(body, force, centre + arm);
      }
      world.step(kDt);
    }
    return world.state_hash();
  };
  EXPECT_EQ(run(true), run(false));
}

// m g applied every step to a body with gravity_scale 0 moves it exactly as gravity would.
TEST(AppliedForces, WeightAsAForceIsGravity) {
  const auto fall = [](bool as_force) {
    World world;
    BodyDef def;  // 1 kg
    def.gravity_scale = as_force ? 0.0 : 1.0;
    const BodyId body = world.create_body(def);
    for (int i = 0; i < 60; ++i) {
      if (as_force) world.apply_force(body, world.settings().gravity, world.body(body).position);
      world.step(kDt);
    }
    return world.body(body);
  };
  const BodyState by_gravity = fall(false), by_force = fall(true);
  EXPECT_EQ(by_force.position, by_gravity.position);
  EXPECT_EQ(by_force.linear_velocity, by_gravity.linear_velocity);
}

// "Only what the scene calls for": the Forces stage is planned only while a force is pending.
TEST(AppliedForces, PlannedOnlyWhileABodyHasOne) {
  World world(weightless());
  const BodyId body = world.create_body(BodyDef{});
  world.step(kDt);
  EXPECT_FALSE(world.step_plan().forces);
  EXPECT_FALSE(has_stage(world.step_plan(), PlanStage::Forces));
  const std::uint64_t builds = world.step_plan().builds;
  world.apply_torque(body, {0.0, 1e-3, 0.0});
  EXPECT_TRUE(world.step_plan().forces);
  EXPECT_TRUE(has_stage(world.step_plan(), PlanStage::Forces));
  world.step(kDt);
  EXPECT_FALSE(world.step_plan().forces);
  EXPECT_FALSE(has_stage(world.step_plan(), PlanStage::Forces));
  EXPECT_EQ(world.step_plan().builds, builds) << "forces toggle the plan, never rebuild it";
}

TEST(AppliedForces, BitIdenticalAcrossWidthsAndWakeASleepingBody) {
  std::uint64_t reference = 0;
  for (SimdWidth width : test::kEveryWidth) {
    if (!test::cpu_runs(width)) continue;
    try {
      World world(weightless(width));
      std::vector<BodyId> bodies;
      for (int i = 0; i < 12; ++i) {  // more than a block of 8
        BodyDef def;
        def.position = {double(i), 0.0, 0.0};
        def.angular_damping = 0.1 * i;
        bodies.push_back(world.create_body(def));
      }
      for (int step = 0; step < 60; ++step) {
        if (step % 3 == 0) {
          world.apply_force(bodies[static_cast<std::size_t>(step % 11)], {0.3, -0.2, 0.1},
                            {0.0, 1.0, 0.0});
        }
        world.step(kDt);
      }
      // Body 11 is never pushed: it rests and falls asleep; a torque wakes it.
      for (int i = 0; i < 120; ++i) world.step(kDt);
      EXPECT_FALSE(world.is_awake(bodies[11]));
      world.apply_torque(bodies[11], {0.0, 0.0, 0.5});
      EXPECT_TRUE(world.is_awake(bodies[11]));
      world.step(kDt);
      EXPECT_GT(world.body(bodies[11]).angular_velocity.z(), 0.0);
      if (reference == 0) reference = world.state_hash();
      EXPECT_EQ(world.state_hash(), reference) << simd_width_name(width);
    } catch (const InvalidArgument&) {
      // width not available on this CPU
    }
  }
}

TEST(AppliedForces, BadInputIsRejectedAndChangesNothing) {
  World world;
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId fixed = world.create_body(ground);
  const BodyId body = world.create_body(BodyDef{});
  world.apply_force(body, {1e9, 0.0, 0.0}, {0.0, 0.0, 0.0});
  world.step(kDt);
  world.apply_force(body, {1e9, 0.0, 0.0}, world.body(body).position);  // pending, at the limit
  const std::uint64_t before = world.state_hash();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto rejects = [&](const std::function<void()>& call, const std::string& field,
                           const std::string& value) {
    expect_invalid_argument(call, field, value);
    EXPECT_EQ(world.state_hash(), before) << field;
  };
  rejects([&] { world.apply_force(fixed, {1, 0, 0}, {0, 0, 0}); }, "body", "static");
  rejects([&] { world.apply_force(body, {nan, 0, 0}, {0, 0, 0}); }, "force", "nan");
  rejects([&] { world.apply_force(body, {1, 0, 0}, {0, nan, 0}); }, "world_point", "nan");
  rejects(
      [&] {
        world.apply_torque(body, {0, 0, -std::numeric_limits<double>::infinity()});
      },
      "torque", "inf");
  // The pending 1e9 N plus 1 N would leave the float envelope.
  rejects(
      [&] {
        world.apply_force(body, {1.0, 0, 0}, world.body(body).position);
      },
      "force", "for the next step");
  rejects(
      [&] {
        world.apply_force(body, {0, 1e5, 0},
                          world.body(body).position + Eigen::Vector3d(1e5, 0, 0));
      },
      "force", "torque");
  rejects([&] { world.apply_torque(BodyId{}, {0, 0, 1}); }, "body", "no such body");
}

}  // namespace
}  // namespace softstep
