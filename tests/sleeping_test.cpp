// Sleeping islands: an island at rest falls asleep after time_to_sleep, costs no solver
// work while asleep, wakes on every event that can move it, and never changes what an
// awake island does.
#include <gtest/gtest.h>

#include <functional>

#include "frame_constants.hpp"
#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

using test::kDt;

WorldSettings resting_settings() {
  WorldSettings s;
  s.gravity.setZero();  // a chain laid out at rest stays at rest
  s.time_to_sleep = 0.25;
  return s;
}

scenes::ChainScene resting_chain(World& world) {
  scenes::ChainOptions o;
  o.links = 10;
  return scenes::build_chain(world, o);
}

// Steps until the chain sleeps; returns how many steps it took (or -1 after `limit`).
int steps_to_sleep(World& world, BodyId body, int limit) {
  for (int i = 1; i <= limit; ++i) {
    world.step(kDt);
    if (!world.is_awake(body)) return i;
  }
  return -1;
}

TEST(Sleeping, IslandAtRestFallsAsleepAfterTimeToSleepAndCostsNothing) {
  World world(resting_settings());
  const scenes::ChainScene scene = resting_chain(world);
  const StepPlan& awake = world.step_plan();
  EXPECT_EQ(awake.awake_bodies, 10u);
  EXPECT_EQ(awake.rows_per_pass, 30u);

  // time_to_sleep is 0.25 s: 15 steps of 1/60 s at rest (the sum may round to 16).
  const int steps = steps_to_sleep(world, scene.links[0][5], 100);
  EXPECT_GE(steps, 15);
  EXPECT_LE(steps, 16);
  for (BodyId b : scene.links[0]) EXPECT_FALSE(world.is_awake(b));

  const StepPlan& asleep = world.step_plan();
  EXPECT_EQ(asleep.awake_bodies, 0u);
  EXPECT_EQ(asleep.sleeping_islands, 1u);
  EXPECT_EQ(asleep.rows_per_pass, 0u);  // no row is solved while asleep
  EXPECT_TRUE(asleep.kernels.empty());
  EXPECT_TRUE(asleep.stages.empty());
  // Nothing changes while asleep, not even a rest timer: the step does no work on it.
  const std::uint64_t before = world.state_hash();
  for (int i = 0; i < 30; ++i) world.step(kDt);
  EXPECT_EQ(world.state_hash(), before);
}

TEST(Sleeping, ConfiguredTimeIsHonoured) {
  WorldSettings s = resting_settings();
  s.time_to_sleep = 1.0;
  World world(s);
  const scenes::ChainScene scene = resting_chain(world);
  const int steps = steps_to_sleep(world, scene.links[0][0], 200);
  EXPECT_GE(steps, 60);
  EXPECT_LE(steps, 61);
}

TEST(Sleeping, NeverSleepKeepsTheIslandAwakeAndSettingOffKeepsAllAwake) {
  World world(resting_settings());
  const scenes::ChainScene scene = resting_chain(world);
  BallJointDef j;
  BodyDef restless;
  restless.never_sleep = true;
  restless.position = world.body(scene.links[0].back()).position + Eigen::Vector3d(0.25, 0, 0);
  j.body_a = scene.links[0].back();
  j.body_b = world.create_body(restless);
  j.local_anchor_a = {0.125, 0.0, 0.0};
  j.local_anchor_b = {-0.125, 0.0, 0.0};
  world.create_ball_joint(j);
  EXPECT_EQ(steps_to_sleep(world, scene.links[0][0], 120), -1);

  WorldSettings off = resting_settings();
  off.sleeping = false;
  World other(off);
  const scenes::ChainScene chain = resting_chain(other);
  EXPECT_EQ(steps_to_sleep(other, chain.links[0][0], 120), -1);
}

// One sleeping chain per event; each event on one link wakes the whole chain.
TEST(Sleeping, WakesOnEveryEvent) {
  using Event = std::function<void(World&, const scenes::ChainScene&)>;
  const std::vector<std::pair<const char*, Event>> events = {
      {"set_linear_velocity",
       [](World& w, const auto& s) {
         w.set_linear_velocity(s.links[0][4], {0, 1, 0});
       }},
      {"set_angular_velocity",
       [](World& w, const auto& s) {
         w.set_angular_velocity(s.links[0][4], {0, 1, 0});
       }},
      {"set_position",
       [](World& w, const auto& s) {
         w.set_position(s.links[0][4], w.body(s.links[0][4]).position);
       }},
      {"set_orientation",
       [](World& w, const auto& s) {
         w.set_orientation(s.links[0][4], w.body(s.links[0][4]).orientation);
       }},
      {"set_mass_properties",
       [](World& w, const auto& s) {
         w.set_mass_properties(s.links[0][4], 2.0, solid_sphere_inertia(2.0, 0.1));
       }},
      {"apply_impulse",
       [](World& w, const auto& s) {
         w.apply_impulse(s.links[0][4], {0, 0, 0.5}, w.body(s.links[0][4]).position);
       }},
      {"destroy_joint", [](World& w, const auto& s) { w.destroy_joint(s.joints[4]); }},
      {"joint added on it",
       [](World& w, const auto& s) {
         DistanceJointDef j;
         j.body_a = s.anchors[0];
         j.body_b = s.links[0][4];
         j.rest_length = (w.body(s.links[0][4]).position - w.body(s.anchors[0]).position).norm();
         w.create_distance_joint(j);
       }},
      {"joint to an awake body",
       [](World& w, const auto& s) {
         BodyDef d;
         d.position = w.body(s.links[0][9]).position + Eigen::Vector3d(0.0, -0.3, 0.0);
         BallJointDef j;
         j.body_a = s.links[0][9];
         j.body_b = w.create_body(d);
         j.local_anchor_b = {0.0, 0.3, 0.0};
         w.create_ball_joint(j);
       }},
      {"destroy_body", [](World& w, const auto& s) { w.destroy_body(s.links[0][9]); }},
  };
  for (const auto& [name, event] : events) {
    World world(resting_settings());
    const scenes::ChainScene scene = resting_chain(world);
    ASSERT_GT(steps_to_sleep(world, scene.links[0][0], 100), 0) << name;
    event(world, scene);
    EXPECT_TRUE(world.is_awake(scene.links[0][0])) << name;
    EXPECT_TRUE(world.is_awake(scene.links[0][4])) << name;
    EXPECT_EQ(world.step_plan().sleeping_islands, 0u) << name;
    EXPECT_GT(world.step_plan().rows_per_pass, 0u) << name;
  }
}

// The impulse shows in the velocities: dv = J / m, dw = I^-1 (r x J).
TEST(Sleeping, ApplyImpulseChangesVelocitiesByTheImpulse) {
  World world(resting_settings());
  BodyDef d;
  d.mass = 2.0;
  d.inertia = solid_sphere_inertia(2.0, 0.1);
  const BodyId body = world.create_body(d);
  world.apply_impulse(body, {0.0, 0.0, 1.0}, {0.1, 0.0, 0.0});
  const BodyState s = world.body(body);
  EXPECT_NEAR((s.linear_velocity - Eigen::Vector3d(0, 0, 0.5)).norm(), 0.0, 1e-12);
  // r x J = (0.1, 0, 0) x (0, 0, 1) = (0, -0.1, 0); I = 0.008
  EXPECT_NEAR((s.angular_velocity - Eigen::Vector3d(0, -0.1 / 0.008, 0)).norm(), 0.0, 1e-9);
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId fixed = world.create_body(ground);
  EXPECT_THROW(world.apply_impulse(fixed, {1, 0, 0}, {0, 0, 0}), InvalidArgument);
}

// Island X swings; island Y, a resting chain beside it, falls asleep. X's trajectory is the
// one it has in a world without Y, bit for bit, before and after Y sleeps.
TEST(Sleeping, SleepingNeighbourLeavesAnAwakeIslandBitIdentical) {
  const auto swinging = [](World& world) {
    scenes::ChainOptions o;
    o.links = 12;
    return scenes::build_chain(world, o);
  };
  WorldSettings s;
  s.time_to_sleep = 0.25;
  World alone(s);
  const scenes::ChainScene x_alone = swinging(alone);
  World shared(s);
  const scenes::ChainScene x = swinging(shared);
  // Y: a chain resting on the ground in gravity, held by rigid joints to static posts.
  BodyDef post;
  post.type = BodyType::Static;
  std::vector<BodyId> y;
  for (int i = 0; i < 8; ++i) {
    BodyDef d;
    d.position = {0.25 * i, -5.0, 3.0};
    y.push_back(shared.create_body(d));
    post.position = d.position + Eigen::Vector3d(0.0, 0.5, 0.0);
    BallJointDef j;
    j.body_a = shared.create_body(post);
    j.body_b = y.back();
    j.local_anchor_a = {0.0, -0.5, 0.0};
    shared.create_ball_joint(j);
    if (i > 0) {
      DistanceJointDef link;
      link.body_a = y[y.size() - 2];
      link.body_b = y.back();
      link.rest_length = 0.25;
      shared.create_distance_joint(link);
    }
  }
  bool y_slept = false;
  for (int step = 0; step < 120; ++step) {
    alone.step(kDt);
    shared.step(kDt);
    y_slept |= !shared.is_awake(y[0]);
    for (std::size_t i = 0; i < x.links[0].size(); ++i) {
      const BodyState a = alone.body(x_alone.links[0][i]);
      const BodyState b = shared.body(x.links[0][i]);
      ASSERT_EQ(a.position, b.position) << "step " << step << " link " << i;
      ASSERT_EQ(a.orientation.coeffs(), b.orientation.coeffs()) << "step " << step;
      ASSERT_EQ(a.linear_velocity, b.linear_velocity) << "step " << step;
    }
  }
  EXPECT_TRUE(y_slept) << "the neighbour must fall asleep for the test to mean anything";
  EXPECT_TRUE(shared.is_awake(x.links[0][0]));
}

// Falling asleep and waking are decided on the double-precision state in slot order, so they
// happen on the same step at every width and thread count.
TEST(Sleeping, IsDeterministicAcrossWidths) {
  const auto run = [](SimdWidth width) {
    WorldSettings s = resting_settings();
    s.gravity = {0.0, -9.81, 0.0};
    s.simd = width;
    World world(s);
    scenes::ChainOptions o;
    o.links = 8;
    o.chains = 3;
    o.layout = scenes::ChainLayout::Hanging;
    const scenes::ChainScene scene = scenes::build_chain(world, o);
    for (int i = 0; i < 240; ++i) {
      world.step(kDt);
      if (i == 150) {
        EXPECT_FALSE(world.is_awake(scene.links[1][7])) << "the chains must have slept";
        world.apply_impulse(scene.links[1][7], {0.2, 0, 0}, {0, 0, 0});
      }
    }
    return world.state_hash();
  };
  const std::uint64_t scalar = run(SimdWidth::Scalar);
  EXPECT_EQ(run(SimdWidth::Best), scalar);
}

}  // namespace
}  // namespace softstep

namespace softstep {
namespace {

// Issue 17, bug 2: a body created 3 m from a static body on a rigid ball joint (or a 1 m rope)
// is pulled in by the bounded correction, which the relax pass then takes out of its velocity:
// the body moved every step while its velocity read zero, and the island fell asleep with the
// joint 1.6 m open for good. A body that the correction still moves is not at rest.
double error_when_asleep(bool rope) {
  WorldSettings s;
  s.gravity.setZero();
  World world(s);
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId anchor = world.create_body(ground);
  BodyDef body;
  body.position = {3.0, 0.0, 0.0};
  const BodyId ball = world.create_body(body);
  JointId joint;
  if (rope) {
    DistanceJointDef d;
    d.body_a = anchor;
    d.body_b = ball;
    d.spring = Spring::free();
    d.max_length = 1.0;
    joint = world.create_distance_joint(d);
  } else {
    BallJointDef b;
    b.body_a = anchor;
    b.body_b = ball;
    joint = world.create_ball_joint(b);
  }
  for (int i = 0; i < 600 && world.is_awake(ball); ++i) world.step(kDt);
  EXPECT_FALSE(world.is_awake(ball)) << "a closed joint at rest falls asleep within 10 s";
  return world.joint_reading(joint).error;
}

TEST(Sleeping, AViolatedJointKeepsItsIslandAwakeUntilItCloses) {
  EXPECT_LT(error_when_asleep(false), 1e-3) << "rigid ball joint";
  EXPECT_LT(error_when_asleep(true), 1e-3) << "rope";
}

}  // namespace
}  // namespace softstep
