// The step profile records every stage it ran, once per step or per sub-step, in order, and
// nothing for a stage the step did not run.
#include <gtest/gtest.h>

#include <numeric>

#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

std::vector<Stage> stages_of(const StepProfile& p) {
  std::vector<Stage> out;
  for (const StageEvent& e : p.thread_events.at(0)) out.push_back(e.stage);
  return out;
}

TEST(Profile, RecordsEveryStageOncePerStepOrSubstep) {
  WorldSettings s;
  s.substeps = 2;
  World world(s);
  scenes::ChainOptions o;
  o.links = 10;
  scenes::build_chain(world, o);
  world.set_profiling(true);
  world.step(1.0 / 60.0);
  const StepProfile& p = world.last_step_profile();
  const std::vector<Stage> expected = {Stage::Prepare,
                                       Stage::IntegrateVelocities,
                                       Stage::WarmStart,
                                       Stage::Solve,
                                       Stage::IntegratePositions,
                                       Stage::Relax,
                                       Stage::IntegrateVelocities,
                                       Stage::WarmStart,
                                       Stage::Solve,
                                       Stage::IntegratePositions,
                                       Stage::Relax,
                                       Stage::Store};
  EXPECT_EQ(stages_of(p), expected);
  const double staged = std::accumulate(p.stage_ms.begin(), p.stage_ms.end(), 0.0);
  EXPECT_GT(staged, 0.0);
  EXPECT_LE(staged, p.step_ms);
  for (std::size_t i = 1; i < p.thread_events[0].size(); ++i) {
    EXPECT_GE(p.thread_events[0][i].start_us, p.thread_events[0][i - 1].end_us);
  }
}

TEST(Profile, StagesWithNoWorkAreNotRun) {
  WorldSettings s;
  s.substeps = 1;
  s.relax_iterations = 0;
  World world(s);
  BodyDef lone;  // a body with no joint: no warm start, solve or relax
  world.create_body(lone);
  world.set_profiling(true);
  world.step(1.0 / 60.0);
  const std::vector<Stage> expected = {Stage::Prepare, Stage::IntegrateVelocities,
                                       Stage::IntegratePositions, Stage::Store};
  EXPECT_EQ(stages_of(world.last_step_profile()), expected);
}

TEST(Profile, OffRecordsNothing) {
  World world;
  world.create_body(BodyDef{});
  world.step(1.0 / 60.0);
  EXPECT_TRUE(world.last_step_profile().thread_events.empty());
}

}  // namespace
}  // namespace softstep
