// The kernels are written once over the lane type, and fusion is a build-wide choice, so the
// scalar, SSE and AVX2 paths must give bit-identical worlds (DESIGN.md, "Kernels are written
// once").
#include <gtest/gtest.h>

#include <ostream>

#include "scenes/chain_scene.hpp"

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
  for (SimdWidth w : {SimdWidth::Sse, SimdWidth::Avx2}) {
    try {
      EXPECT_EQ(run_chain(w, v, 1000, 300), scalar) << v.name << " width " << static_cast<int>(w);
      ++compared;
    } catch (const InvalidArgument&) {
      // this CPU lacks the width; the portable CI job still compares the rest
    }
  }
  EXPECT_GT(compared, 0) << "no wide path available to compare";
}

INSTANTIATE_TEST_SUITE_P(
    Chains, SimdWidths,
    ::testing::Values(Variant{scenes::ChainJoint::Ball, Spring::rigid(), "rigid_ball"},
                      Variant{scenes::ChainJoint::Ball, Spring::soft(5.0, 0.3), "soft_ball"},
                      Variant{scenes::ChainJoint::Distance, Spring::rigid(), "rigid_distance"},
                      Variant{scenes::ChainJoint::Distance, Spring::soft(8.0, 0.1),
                              "soft_distance"}),
    [](const ::testing::TestParamInfo<Variant>& p) { return std::string(p.param.name); });

// The widths really differ in layout: the same chain packs into 1-, 4- and 8-lane groups.
TEST(SimdWidths, LayoutReportsTheLaneCount) {
  for (auto [width, lanes] : {std::pair{SimdWidth::Scalar, 1}, std::pair{SimdWidth::Avx2, 8}}) {
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
  for (SimdWidth w : {SimdWidth::Scalar, SimdWidth::Sse, SimdWidth::Avx2}) {
    try {
      EXPECT_EQ(run(2, w), reference) << simd_width_name(w);
      EXPECT_EQ(run(1, w), reference) << simd_width_name(w);
      EXPECT_EQ(run(0, w), reference) << simd_width_name(w);  // 0: all of the machine's cores
    } catch (const InvalidArgument&) {
      // width not available on this CPU
    }
  }
}

}  // namespace
}  // namespace softstep
