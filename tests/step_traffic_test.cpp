// The memory-traffic model (softstep/step_traffic.hpp) counts what the plan runs and nothing
// else, grows with the content as the data does, and counts each pass it runs.
#include <gtest/gtest.h>

#include "contacts/analytic_contacts.hpp"
#include "scenes/chain_scene.hpp"
#include "softstep/step_traffic.hpp"

namespace softstep {
namespace {

double bytes(const StepTraffic& t, Stage s) { return t.bytes[static_cast<std::size_t>(s)]; }

StepTraffic chain_traffic(int chains, WorldSettings s) {
  s.simd = SimdWidth::Scalar;  // one lane per group: no padding lanes to blur the proportions
  s.sleeping = false;
  World world(s);
  scenes::ChainOptions o;
  o.links = 100;
  o.chains = chains;
  scenes::build_chain(world, o);
  world.step(1.0 / 60.0);
  return step_traffic(world);
}

TEST(StepTraffic, EveryStageOfAChainStepMovesBytesAndTheyAddUp) {
  const StepTraffic t = chain_traffic(1, WorldSettings{});
  double sum = 0.0;
  for (int st = 0; st < kStageCount; ++st) {
    const auto i = static_cast<std::size_t>(st);
    sum += t.bytes[i];
    if (static_cast<Stage>(st) == Stage::Restitution) {
      EXPECT_EQ(t.bytes[i], 0.0) << "no contacts, no restitution pass";
    } else {
      EXPECT_GT(t.bytes[i], 0.0) << stage_name(static_cast<Stage>(st));
      EXPECT_GT(t.units[i], 0.0) << stage_name(static_cast<Stage>(st));
    }
  }
  EXPECT_DOUBLE_EQ(t.total(), sum);
}

TEST(StepTraffic, TwiceTheChainsMoveTwiceTheBytesInEveryStage) {
  const StepTraffic one = chain_traffic(3, WorldSettings{});
  const StepTraffic two = chain_traffic(6, WorldSettings{});
  for (int st = 0; st < kStageCount; ++st) {
    const auto i = static_cast<std::size_t>(st);
    EXPECT_DOUBLE_EQ(two.bytes[i], 2.0 * one.bytes[i]) << stage_name(static_cast<Stage>(st));
    if (one.units[i] > 0.0) {
      EXPECT_DOUBLE_EQ(two.bytes[i] / two.units[i], one.bytes[i] / one.units[i])
          << "bytes per row or body do not depend on the size";
    }
  }
}

TEST(StepTraffic, EachPassIsCountedAndStagesThePlanSkipsMoveNothing) {
  WorldSettings s;
  const StepTraffic base = chain_traffic(1, s);
  s.solve_iterations = 3;
  s.relax_iterations = 2;
  const StepTraffic more = chain_traffic(1, s);
  EXPECT_DOUBLE_EQ(bytes(more, Stage::Solve), 3.0 * bytes(base, Stage::Solve));
  EXPECT_DOUBLE_EQ(bytes(more, Stage::Relax), 2.0 * bytes(base, Stage::Relax));
  EXPECT_DOUBLE_EQ(bytes(more, Stage::Prepare), bytes(base, Stage::Prepare));
  s = WorldSettings{};
  s.substeps = 8;  // twice the default's sub-steps: twice every per-sub-step stage's bytes
  const StepTraffic finer = chain_traffic(1, s);
  for (Stage st : {Stage::IntegrateVelocities, Stage::WarmStart, Stage::Solve,
                   Stage::IntegratePositions, Stage::Relax}) {
    EXPECT_DOUBLE_EQ(bytes(finer, st), 2.0 * bytes(base, st)) << stage_name(st);
  }
  EXPECT_DOUBLE_EQ(bytes(finer, Stage::Store), bytes(base, Stage::Store));
  s = WorldSettings{};
  s.warm_start = false;
  s.relax_iterations = 0;
  const StepTraffic plain = chain_traffic(1, s);
  EXPECT_EQ(bytes(plain, Stage::WarmStart), 0.0);
  EXPECT_EQ(bytes(plain, Stage::Relax), 0.0);
  EXPECT_DOUBLE_EQ(bytes(plain, Stage::Solve), bytes(base, Stage::Solve));
}

TEST(StepTraffic, AJointPassReadsAtLeastTheJointsLanesAndBodyRecords) {
  // A ball joint's lane keeps at least its two anchors, its two body indices and its three
  // impulses (11 x 4 bytes); a pass reads and writes each of its bodies' velocity (2 x 32 B).
  const StepTraffic t = chain_traffic(1, WorldSettings{});
  const auto solve = static_cast<std::size_t>(Stage::Solve);
  const double per_joint = 3.0 * t.bytes[solve] / t.units[solve];  // 3 rows per ball joint
  EXPECT_GE(per_joint, 11 * 4 + 64);
  EXPECT_LE(per_joint, 4096.0) << "a joint's whole lane group is not this large";
}

TEST(StepTraffic, ContactsAloneMoveNoJointPassBytesAndNothingIsNaN) {
  // Contact lanes are not modelled: a box on the ground counts its body stages only, and
  // every stage that counts bytes has units to count them per.
  World world;
  const BodyId ground = test::add_ground(world);
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const BodyId box = test::add_box(world, {0.0, 0.5, 0.0}, 10.0, half);
  const ContactManifold m = test::box_on_ground(world, ground, box, half, 0.0, 0.5);
  world.step(1.0 / 60.0, {&m, 1});
  const StepTraffic t = step_traffic(world);
  for (Stage st : {Stage::WarmStart, Stage::Solve, Stage::Relax}) EXPECT_EQ(bytes(t, st), 0.0);
  EXPECT_GT(bytes(t, Stage::Prepare), 0.0);
  for (int st = 0; st < kStageCount; ++st) {
    const auto i = static_cast<std::size_t>(st);
    if (t.bytes[i] > 0.0) {
      EXPECT_GT(t.units[i], 0.0) << stage_name(static_cast<Stage>(st));
    }
  }
}

}  // namespace
}  // namespace softstep
