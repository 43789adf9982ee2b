// The step plan and the feature-specialized kernels: a scene runs only the stages and
// kernel variants its content calls for, and the result is the one the general kernels
// give when fed neutral values (no spring, no limit rows, zero gravity).
#include <gtest/gtest.h>

#include <algorithm>

#include "scenes/chain_scene.hpp"
#include "scenes/feature_zoo.hpp"

namespace softstep {
namespace {

bool has_stage(const StepPlan& p, PlanStage s) { return p.runs(s); }

bool has_row(const StepPlan& p, SpringRow row) {
  return std::any_of(p.kernels.begin(), p.kernels.end(),
                     [&](const PlanKernel& k) { return k.row == row; });
}

std::uint64_t run_zoo(bool specialize, SimdWidth width, const Eigen::Vector3d& gravity,
                      double damping, bool warm_start) {
  WorldSettings s;
  s.specialize = specialize;
  s.simd = width;
  s.gravity = gravity;
  s.warm_start = warm_start;
  World world(s);
  scenes::build_feature_zoo(world, damping);
  for (int i = 0; i < 120; ++i) world.step(1.0 / 60.0);
  EXPECT_GT(world.step_plan().awake_bodies, 0u) << "the zoo must still be moving";
  return world.state_hash();
}

// The specialized kernels leave out only terms that are exactly neutral in the general
// kernel (a zero gravity added, a damping factor of 1, a disabled row's zero impulse, a
// spring's infinite bias bound), so the worlds agree bit for bit, at every width.
TEST(StepPlan, SpecializedKernelsGiveTheGeneralKernelsTrajectoryBitForBit) {
  struct Case {
    Eigen::Vector3d gravity;
    double damping;
    bool warm_start;
  };
  for (const Case& c : {Case{{0.0, -9.81, 0.0}, 0.0, true}, Case{{0.0, 0.0, 0.0}, 0.0, true},
                        Case{{0.0, 0.0, 0.0}, 0.5, true}, Case{{0.0, -9.81, 0.0}, 0.2, false}}) {
    for (SimdWidth width : {SimdWidth::Scalar, SimdWidth::Best}) {
      EXPECT_EQ(run_zoo(true, width, c.gravity, c.damping, c.warm_start),
                run_zoo(false, width, c.gravity, c.damping, c.warm_start))
          << "gravity " << c.gravity.y() << " damping " << c.damping << " width "
          << simd_width_name(width);
    }
  }
}

TEST(StepPlan, ZooRunsOneVariantPerSignature) {
  World world;
  scenes::build_feature_zoo(world, 0.0);
  const StepPlan& plan = world.step_plan();
  // ball: rigid, soft, free; distance: rod, soft+min, soft+max, soft+both, rope, free+min
  EXPECT_EQ(plan.kernels.size(), 9u);
  std::uint32_t joints = 0;
  for (const PlanKernel& k : plan.kernels) {
    EXPECT_NE(k.row, SpringRow::Any) << "the general kernel runs nothing in a specialized plan";
    EXPECT_GT(k.batches, 0u);
    joints += k.joints;
  }
  EXPECT_EQ(joints, world.joint_count());
  EXPECT_TRUE(plan.springs);
  EXPECT_TRUE(plan.limits);
  // Rows: 12 rigid + 12 soft ball joints (3 each), free ball joints none; distance: rods 1,
  // soft + one limit 2, soft + both 3, rope 1, free + min 1 (two of each kind).
  EXPECT_EQ(plan.rows_per_pass, 24u * 3 + 2u * (1 + 2 + 2 + 3 + 1 + 1));

  WorldSettings general;
  general.specialize = false;
  world.set_settings(general);
  const StepPlan& all = world.step_plan();
  ASSERT_EQ(all.kernels.size(), 2u);  // one general kernel per joint type
  for (const PlanKernel& k : all.kernels) EXPECT_EQ(k.row, SpringRow::Any);
}

TEST(StepPlan, SceneWithoutGravityDampingOrSpringsSchedulesNoneOfThem) {
  WorldSettings s;
  s.gravity.setZero();
  World world(s);
  scenes::ChainOptions o;
  o.links = 20;
  scenes::build_chain(world, o);  // rigid ball joints, no damping
  const StepPlan& plan = world.step_plan();
  EXPECT_FALSE(plan.gravity);
  EXPECT_FALSE(plan.damping);
  EXPECT_FALSE(plan.springs);
  EXPECT_FALSE(has_stage(plan, PlanStage::Gravity));
  EXPECT_FALSE(has_stage(plan, PlanStage::Damping));
  EXPECT_FALSE(has_row(plan, SpringRow::Soft));
  EXPECT_FALSE(has_row(plan, SpringRow::Any));
  EXPECT_TRUE(has_stage(plan, PlanStage::Solve));
  EXPECT_TRUE(has_stage(plan, PlanStage::Relax));  // rigid rows are relaxed

  // The same scene with gravity, damping and springs schedules each of them.
  WorldSettings with = s;
  with.gravity = {0.0, -9.81, 0.0};
  World other(with);
  o.spring = Spring::soft(5.0, 0.5);
  const scenes::ChainScene scene = scenes::build_chain(other, o);
  BodyDef damped;
  damped.linear_damping = 0.1;
  other.create_body(damped);
  const StepPlan& full = other.step_plan();
  EXPECT_TRUE(has_stage(full, PlanStage::Gravity));
  EXPECT_TRUE(has_stage(full, PlanStage::Damping));
  EXPECT_TRUE(has_row(full, SpringRow::Soft));
  EXPECT_TRUE(full.unconstrained_bodies);
  // Springs only: nothing to relax (springs are solved once per sub-step), so no relax pass.
  EXPECT_FALSE(has_stage(full, PlanStage::Relax));
  EXPECT_EQ(scene.joints.size(), 20u);
}

TEST(StepPlan, IsRebuiltOnlyWhenTheContentChanges) {
  WorldSettings s;
  s.sleeping = false;
  World world(s);
  scenes::ChainOptions o;
  o.links = 10;
  const scenes::ChainScene scene = scenes::build_chain(world, o);
  world.step(1.0 / 60.0);
  const std::uint64_t builds = world.step_plan().builds;
  for (int i = 0; i < 10; ++i) world.step(1.0 / 60.0);
  EXPECT_EQ(world.step_plan().builds, builds);
  world.set_linear_velocity(scene.links[0][3], {1.0, 0.0, 0.0});  // state, not content
  world.step(1.0 / 60.0);
  EXPECT_EQ(world.step_plan().builds, builds);
  world.destroy_joint(scene.joints.back());
  EXPECT_EQ(world.step_plan().builds, builds + 1);
  EXPECT_EQ(world.step_plan().rows_per_pass, 9u * 3);
}

// A world with nothing but resting bodies in zero gravity and no joints still moves them:
// the plan keeps the integration, not the joint stages.
TEST(StepPlan, BodiesWithoutJointsIntegrateWithoutJointStages) {
  WorldSettings s;
  s.gravity.setZero();
  World world(s);
  BodyDef d;
  d.linear_velocity = {1.0, 0.0, 0.0};
  const BodyId body = world.create_body(d);
  const StepPlan& plan = world.step_plan();
  EXPECT_FALSE(has_stage(plan, PlanStage::PrepareJoints));
  EXPECT_FALSE(has_stage(plan, PlanStage::Solve));
  EXPECT_FALSE(has_stage(plan, PlanStage::WarmStart));
  EXPECT_FALSE(has_stage(plan, PlanStage::Relax));
  for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
  EXPECT_NEAR(world.body(body).position.x(), 1.0, 1e-5);
}

}  // namespace
}  // namespace softstep
