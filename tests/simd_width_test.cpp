// The kernels are written once over the lane type, and fusion is a build-wide choice, so the
// scalar, SSE, AVX2 and AVX-512 paths must give bit-identical worlds (DESIGN.md, "Kernels are written
// once").
#include <gtest/gtest.h>

#include <ostream>
#include <thread>
#include <vector>

#include "scenes/chain_scene.hpp"
#include "simd_widths.hpp"

namespace softstep {
namespace {

struct Variant {
  scenes::ChainJoint joint;
  Spring spring;
  const char* name;
};

std::uint64_t run_chain(SimdWidth width, const Variant& v, int links, int steps) {
  WorldSettings s;
  s.simd = width;
  World world(s);
  scenes::ChainOptions o;
  o.links = links;
  o.joint = v.joint;
  o.spring = v.spring;
  scenes::build_chain(world, o);
  for (int i = 0; i < steps; ++i) world.step(1.0 / 60.0);
  return world.state_hash();
}

void PrintTo(const Variant& v, std::ostream* os) {
  *os << v.name;
}

class SimdWidths : public ::testing::TestWithParam<Variant> {};

TEST_P(SimdWidths, ChainIsBitIdenticalAcrossWidths) {
  const Variant v = GetParam();
  const std::uint64_t scalar = run_chain(SimdWidth::Scalar, v, 1000, 300);
  int compared = 0;
  for (SimdWidth w : test::kEveryWidth) {
    if (w == SimdWidth::Scalar || !test::cpu_runs(w)) continue;
    EXPECT_EQ(run_chain(w, v, 1000, 300), scalar) << v.name << " width " << simd_width_name(w);
    ++compared;
  }
  EXPECT_GT(compared, 0) << "no wide path available to compare";
}

INSTANTIATE_TEST_SUITE_P(
    Chains, SimdWidths,
    ::testing::Values(Variant{scenes::ChainJoint::Ball, Spring::rigid(), "rigid_ball"},
                      Variant{scenes::ChainJoint::Ball, Spring::soft(5.0, 0.3), "soft_ball"},
                      Variant{scenes::ChainJoint::Distance, Spring::rigid(), "rigid_distance"},
                      Variant{scenes::ChainJoint::Distance, Spring::soft(8.0, 0.1),
                              "soft_distance"},
                      Variant{scenes::ChainJoint::Distance, Spring::absolute(1000.0, 5.0),
                              "absolute_distance"}),
    [](const ::testing::TestParamInfo<Variant>& p) { return std::string(p.param.name); });

// The widths really differ in layout: the same chain packs into 1-, 4-, 8- and 16-lane groups.
TEST(SimdWidths, LayoutReportsTheLaneCount) {
  for (auto [width, lanes] : {std::pair{SimdWidth::Scalar, 1}, std::pair{SimdWidth::Sse, 4},
                              std::pair{SimdWidth::Avx2, 8}, std::pair{SimdWidth::Avx512, 16}}) {
    if (!test::cpu_runs(width)) continue;
    WorldSettings s;
    s.simd = width;
    World world(s);
    scenes::ChainOptions o;
    o.links = 100;
    scenes::build_chain(world, o);
    const SolverLayout layout = world.solver_layout();
    EXPECT_EQ(layout.lanes, lanes);
    EXPECT_EQ(layout.colors_used, 2);
    EXPECT_EQ(layout.overflow_joints, 0u);
  }
}

// A width this CPU lacks, or this build left out (SOFTSTEP_WIDTHS), is refused when the world
// is made, naming the field, the width and what is missing; the other widths build a world.
TEST(SimdWidths, AWidthTheCpuLacksIsRefusedNamingWhatItLacks) {
  const char* const isa[] = {"", "SSE4.2", "AVX2", "AVX-512"};
  const std::string built = "," SOFTSTEP_BUILT_WIDTHS ",";  // the tests' CMakeLists
  int refused = 0;
  for (int i = 0; i < 4; ++i) {
    const SimdWidth w = test::kEveryWidth[i];
    const bool in_build = built.find(std::string(",") + simd_width_name(w) + ",") != built.npos;
    WorldSettings s;
    s.simd = w;
    try {
      World world(s);
      EXPECT_TRUE(in_build) << simd_width_name(w);
      EXPECT_EQ(world.solver_layout().simd, w);
    } catch (const InvalidArgument& e) {
      ++refused;
      const std::string message = e.what();
      EXPECT_NE(message.find("WorldSettings.simd"), std::string::npos) << message;
      EXPECT_NE(message.find(simd_width_name(w)), std::string::npos) << message;
      const std::string reason = in_build ? std::string("this CPU lacks ") + isa[i]
                                          : std::string("SOFTSTEP_WIDTHS");
      EXPECT_NE(message.find(reason), std::string::npos) << message;
    }
  }
  if (refused == 0) GTEST_SKIP() << "this CPU has every width: no refusal to check";
}

}  // namespace
}  // namespace softstep

namespace softstep {
namespace {

// Colours split statically over the threads with a barrier per colour and the overflow set on
// one thread: the result cannot depend on the thread count (DESIGN.md, "Parallel and
// deterministic"). The chain is big enough (6,001 bodies and joints) that two threads do run.
TEST(Threads, TwoThreadsAreBitIdenticalToOneAtEveryWidth) {
  const auto run = [](int threads, SimdWidth width) {
    WorldSettings s;
    s.threads = threads;
    s.simd = width;
    World world(s);
    scenes::ChainOptions o;
    o.links = 3000;
    o.spring = Spring::soft(20.0, 0.5);
    scenes::build_chain(world, o);
    // 130 steps: past the adaptive thread count's first probe (every 64 steps).
    for (int i = 0; i < 130; ++i) world.step(1.0 / 60.0);
    return world.state_hash();
  };
  const std::uint64_t reference = run(1, SimdWidth::Scalar);
  for (SimdWidth w : test::kEveryWidth) {
    if (!test::cpu_runs(w)) continue;
    EXPECT_EQ(run(2, w), reference) << simd_width_name(w);
    EXPECT_EQ(run(1, w), reference) << simd_width_name(w);
    EXPECT_EQ(run(0, w), reference) << simd_width_name(w);  // 0: all of the machine's cores
  }
}

// Every stage's threaded path: distance joints with both limit rows, a hub whose joints
// overflow the colours (run on one thread after them), a kinematic driver, profiling (events
// per thread), and both warm starting and cleared impulses. Threads 2 must match threads 1
// bit for bit. This is also the test ThreadSanitizer runs (README, "Tests").
TEST(Threads, EveryStagePathIsBitIdenticalOnTwoThreads) {
  const auto run = [](int threads, bool warm_start) {
    WorldSettings s;
    s.threads = threads;
    s.warm_start = warm_start;
    World world(s);
    world.set_profiling(true);
    scenes::ChainOptions o;
    o.links = 3500;  // enough awake work to share: 3,502 bodies + 3,541 rows / 3
    o.joint = scenes::ChainJoint::Distance;
    o.spring = Spring::soft(15.0, 0.3);
    const scenes::ChainScene chain = scenes::build_chain(world, o);
    BodyDef hub_def;  // dynamic: its joints all share it, so they cannot share colours
    hub_def.position = {0.0, 2.0, 0.0};
    hub_def.mass = 100.0;
    hub_def.gravity_scale = 0.0;
    const BodyId hub = world.create_body(hub_def);
    BodyDef driver_def;
    driver_def.type = BodyType::Kinematic;
    driver_def.position = {0.0, 3.0, 0.0};
    driver_def.linear_velocity = {0.0, 0.0, 0.5};
    DistanceJointDef drive;
    drive.body_a = world.create_body(driver_def);
    drive.body_b = hub;
    drive.spring = Spring::soft(2.0, 1.0);
    drive.rest_length = 1.0;
    world.create_distance_joint(drive);
    for (std::size_t i = 0; i < 40; ++i) {  // more than the 24 colours: an overflow set
      DistanceJointDef d;
      d.body_a = hub;
      d.body_b = chain.links[0][i * 80];
      d.spring = Spring::free();
      d.min_length = 0.5;
      d.max_length = 4.0 + 0.1 * static_cast<double>(i);
      world.create_distance_joint(d);
    }
    int shared_steps = 0;
    for (int i = 0; i < 70; ++i) {  // past the first thread probe (64)
      world.step(1.0 / 60.0);
      shared_steps += world.last_step_profile().threads > 1 ? 1 : 0;
    }
    EXPECT_GT(world.solver_layout().overflow_joints, 0u);
    // The adaptive policy runs the first step and every probe on all threads, whatever the
    // machine's load; with one core there is nothing to share.
    if (threads > 1 && std::thread::hardware_concurrency() > 1) {
      EXPECT_GE(shared_steps, 2);
    }
    return world.state_hash();
  };
  for (bool warm_start : {true, false}) {
    EXPECT_EQ(run(2, warm_start), run(1, warm_start)) << "warm start " << warm_start;
  }
}

// WorldSettings::solver = DirectForTrees on a single long chain: its island is rooted at its
// centre and split in two parts (TreeSystem::split), which two threads eliminate at once,
// meeting at team barriers (tree_solver.hpp). Stepped whole and stage by stage (a loose body
// far off sends it through the stages), two threads must give one thread's bits. This is also
// ThreadSanitizer's check that the two halves share nothing between barriers.
TEST(Threads, OneLongTreeIslandSharedByTwoThreadsGivesOneThreadsBits) {
  const auto run = [](int threads, bool loose_body) {
    WorldSettings s;
    s.threads = threads;
    s.fixed_threads = true;
    s.solver = SolverMode::DirectForTrees;
    World world(s);
    scenes::ChainOptions o;
    o.links = 400;
    o.tilt = 0.3;
    o.link_masses = std::vector<double>(399, 1.0);
    o.link_masses.push_back(100.0);
    scenes::build_chain(world, o);
    if (loose_body) {
      BodyDef loose;
      loose.position = {1000.0, 0.0, 0.0};
      world.create_body(loose);
    }
    EXPECT_EQ(world.step_plan().tree_islands_split, 1u);
    EXPECT_EQ(world.step_plan().tree_islands_whole, !loose_body);
    for (int i = 0; i < 30; ++i) world.step(1.0 / 60.0);
    return world.state_hash();
  };
  for (bool loose_body : {false, true}) {
    EXPECT_EQ(run(2, loose_body), run(1, loose_body)) << "loose body " << loose_body;
  }
}

}  // namespace
}  // namespace softstep
