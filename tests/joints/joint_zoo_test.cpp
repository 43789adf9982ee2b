// The angular-joint zoo (bench/scenes/joint_zoo.hpp: every revolute, prismatic and weld kind
// with limits, motors, springs, rigid and soft welds, under gravity) lands on the same state,
// bit for bit, at every SIMD width, on 1 and 2 threads, and specialized or general
// (DESIGN.md: "make that a test, not a hope").
#include "scenes/joint_zoo.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <set>
#include <thread>

namespace softstep {
namespace {

struct ZooRun {
  std::uint64_t hash = 0;
  int shared_steps = 0;  // steps that ran on more than one thread
};

// 130 steps: past the adaptive thread count's first probe (every 64 steps). nullopt when
// the CPU lacks the width (the constructor throws InvalidArgument).
std::optional<ZooRun> run_zoo(SimdWidth width, int threads, bool specialize) {
  WorldSettings s;
  s.simd = width;
  s.threads = threads;
  s.specialize = specialize;
  std::optional<World> world;
  try {
    world.emplace(s);
  } catch (const InvalidArgument&) {
    return std::nullopt;
  }
  world->set_profiling(true);  // per-step thread count
  scenes::build_joint_zoo(*world);
  ZooRun r;
  for (int i = 0; i < 130; ++i) {
    world->step(1.0 / 60.0);
    r.shared_steps += world->last_step_profile().threads > 1 ? 1 : 0;
  }
  r.hash = world->state_hash();
  return r;
}

TEST(JointZoo, HasEveryKindAndIsBigEnoughToShare) {
  World world;
  const scenes::JointZooScene zoo = scenes::build_joint_zoo(world);
  EXPECT_EQ(std::set<scenes::ZooJoint>(zoo.kinds.begin(), zoo.kinds.end()).size(),
            static_cast<std::size_t>(scenes::kZooJointKinds));
  EXPECT_GE(world.body_count() + world.joint_count(), 4096u);
  std::set<JointType> types;
  for (const PlanKernel& k : world.step_plan().kernels) types.insert(k.type);
  EXPECT_TRUE(types.contains(JointType::Revolute));
  EXPECT_TRUE(types.contains(JointType::Prismatic));
  EXPECT_TRUE(types.contains(JointType::Weld));
}

TEST(JointZoo, BitIdenticalAcrossWidthsThreadsAndSpecialization) {
  const std::optional<ZooRun> reference = run_zoo(SimdWidth::Scalar, 1, true);
  ASSERT_TRUE(reference);
  int compared = 0;
  for (SimdWidth w : {SimdWidth::Scalar, SimdWidth::Sse, SimdWidth::Avx2}) {
    for (int threads : {1, 2}) {
      for (bool specialize : {true, false}) {
        const std::optional<ZooRun> r = run_zoo(w, threads, specialize);
        if (!r) continue;  // this CPU lacks the width
        ++compared;
        EXPECT_EQ(r->hash, reference->hash)
            << simd_width_name(w) << ", " << threads << " thread(s), specialize " << specialize;
        // The adaptive policy runs the first step and every probe on all threads.
        if (threads > 1 && std::thread::hardware_concurrency() > 1) {
          EXPECT_GE(r->shared_steps, 2) << "the zoo never ran on two threads";
        }
      }
    }
  }
  EXPECT_GE(compared, 8) << "fewer than two widths compared";
}

// The ThreadSanitizer job runs Threads.*: the new kernels' threaded path, once.
TEST(Threads, JointZooTwoThreadsMatchOne) {
  const std::optional<ZooRun> one = run_zoo(SimdWidth::Best, 1, true);
  const std::optional<ZooRun> two = run_zoo(SimdWidth::Best, 2, true);
  ASSERT_TRUE(one && two);
  EXPECT_EQ(two->hash, one->hash);
}

// destroy_joint after a step empties the joint's lane in place instead of re-packing every
// joint (issue 17, item 6). The in-place world must land on the state of one that destroyed
// the same joints and re-packed (a settings change re-packs): a vacated lane that still pulled
// on its bodies, or a plan that kept counting it, would differ.
TEST(JointZoo, DestroyingJointsInPlaceEqualsRepacking) {
  const auto run = [](bool repack) {
    WorldSettings s;
    s.simd = SimdWidth::Scalar;
    World world(s);
    const scenes::JointZooScene zoo = scenes::build_joint_zoo(world, {14, 4});
    for (int i = 0; i < 10; ++i) world.step(1.0 / 60.0);
    // One joint of every kind, mid-chain: its bodies keep other joints in the lanes.
    for (std::size_t j = 1; j < zoo.joints.size(); j += 4) world.destroy_joint(zoo.joints[j]);
    if (repack) {
      WorldSettings general = s;
      general.specialize = false;
      world.set_settings(general);
      world.set_settings(s);
    }
    const std::uint64_t rows = world.step_plan().rows_per_pass;
    for (int i = 0; i < 30; ++i) world.step(1.0 / 60.0);
    return std::pair(world.state_hash(), rows);
  };
  const auto in_place = run(false);
  const auto repacked = run(true);
  EXPECT_EQ(in_place.first, repacked.first);
  EXPECT_EQ(in_place.second, repacked.second);
}

}  // namespace
}  // namespace softstep
