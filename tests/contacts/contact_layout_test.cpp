// A step whose contacts ask for what last step's asked for keeps last step's layout (their
// colours and order) instead of colouring them again (ContactSolver::load). What the layout
// reads: each manifold's bodies and point count, whether it asks for friction, rolling
// resistance and restitution, and whether its bodies move (awake and dynamic). A change in any
// of them lays the contacts out again, and a kept layout is the one colouring again would give.
#include <gtest/gtest.h>

#include <functional>

#include "contacts/analytic_contacts.hpp"

namespace softstep::test {
namespace {

// 2,100 stacks of two boxes on the ground: 4,200 manifolds, enough for the checks to run on
// the step's threads (step.cpp, kMinManifoldsToShare), where the layout may be laid out
// beside them instead.
struct Stacks {
  explicit Stacks(int threads, bool sleeping = false) : world(settings(threads, sleeping)) {
    world.set_profiling(true);
    ground = add_ground(world);
    for (int k = 0; k < 2100; ++k) {
      const double x = 3.0 * k;
      lower.push_back(add_box(world, {x, 0.5, 0.0}, 1.0, kUnitCubeHalf));
      upper.push_back(add_box(world, {x, 1.5, 0.0}, 1.0, kUnitCubeHalf));
    }
  }
  static WorldSettings settings(int threads, bool sleeping) {
    WorldSettings s;
    s.threads = threads;
    s.fixed_threads = true;
    s.sleeping = sleeping;
    s.time_to_sleep = 0.05;
    return s;
  }
  // Per stack: the lower box on the ground, the upper box on the lower one; friction off.
  std::vector<ContactManifold> manifolds() const {
    std::vector<ContactManifold> c;
    for (std::size_t k = 0; k < lower.size(); ++k) {
      c.push_back(box_on_ground(world, ground, lower[k], kUnitCubeHalf, 0.0, 0.0));
      c.push_back(box_on_box(world, lower[k], upper[k], kUnitCubeHalf, 0.0));
    }
    return c;
  }
  // Steps with the manifolds changed by `change`; true when the step kept last step's layout.
  bool step(const std::function<void(std::vector<ContactManifold>&)>& change = {}) {
    std::vector<ContactManifold> c = manifolds();
    if (change) change(c);
    world.step(1.0 / 60.0, c);
    return world.last_step_profile().contact_layout_kept;
  }
  const StepPlan& plan() const { return world.step_plan(); }

  World world;
  BodyId ground;
  std::vector<BodyId> lower, upper;
};

// A manifold between two boxes of different stacks, far apart (speculative: it pushes nothing).
ContactManifold between(const Stacks& s, BodyId a, BodyId b) {
  ContactManifold m = box_on_box(s.world, a, b, kUnitCubeHalf, 0.0);
  for (int k = 0; k < m.point_count; ++k) m.points[static_cast<std::size_t>(k)].separation = 2.0;
  return m;
}

class ContactLayoutKept : public ::testing::TestWithParam<int> {};

TEST_P(ContactLayoutKept, OnlyWhileWhatItReadsHolds) {
  Stacks s(GetParam());
  constexpr std::uint32_t kManifolds = 4200, kPoints = 4 * kManifolds;
  // The first step lays out; the third keeps the layout on any thread count (on two, the
  // second lays out beside the checks and finds its inputs unchanged).
  EXPECT_FALSE(s.step());
  s.step();
  EXPECT_TRUE(s.step());
  EXPECT_EQ(s.plan().contact_colors, 2u);
  EXPECT_FALSE(s.plan().contact_friction);

  const auto each = [](auto set) {
    return [set](std::vector<ContactManifold>& c) {
      for (ContactManifold& m : c) set(m);
    };
  };
  const auto friction = each([](ContactManifold& m) { m.friction = 0.5; });
  EXPECT_FALSE(s.step(friction));
  EXPECT_TRUE(s.plan().contact_friction);
  s.step(friction);
  EXPECT_TRUE(s.step(friction));

  const auto rolling = each([](ContactManifold& m) { m.rolling_resistance = 0.01; });
  EXPECT_FALSE(s.step(rolling));
  EXPECT_TRUE(s.plan().contact_rolling);
  EXPECT_FALSE(s.plan().contact_friction) << "friction back to 0";

  const auto restitution = each([](ContactManifold& m) { m.restitution = 0.5; });
  EXPECT_FALSE(s.step(restitution));
  EXPECT_TRUE(s.plan().contact_restitution);
  s.step(restitution);
  EXPECT_TRUE(s.step(restitution));

  const auto three_points = [](std::vector<ContactManifold>& c) { c[7].point_count = 3; };
  EXPECT_FALSE(s.step(three_points));
  EXPECT_EQ(s.plan().contact_points, kPoints - 1);
  EXPECT_FALSE(s.plan().contact_restitution);
  s.step(three_points);
  EXPECT_TRUE(s.step(three_points));

  // Stack 1's ground contact replaced by one between the lower boxes of stacks 0 and 1: the
  // same count, but stack 0's lower box has colours 0 and 1 by then, so it takes a third.
  const auto repaired = [&](std::vector<ContactManifold>& c) {
    c[2] = between(s, s.lower[0], s.lower[1]);
  };
  EXPECT_FALSE(s.step(repaired));
  EXPECT_EQ(s.plan().contact_colors, 3u);
  s.step(repaired);
  EXPECT_TRUE(s.step(repaired));
  EXPECT_FALSE(s.step());
  EXPECT_EQ(s.plan().contact_colors, 2u);
  EXPECT_EQ(s.plan().contact_manifolds, kManifolds);
}

TEST_P(ContactLayoutKept, NotOnceABodySleepsOrWakes) {
  Stacks s(GetParam(), /*sleeping=*/true);
  int step = 0;
  while (s.world.is_awake(s.lower[0]) && step++ < 200) s.step();
  ASSERT_FALSE(s.world.is_awake(s.lower[0])) << "the stacks came to rest";
  ASSERT_FALSE(s.world.is_awake(s.upper.back()));
  // Asleep, their manifolds are left out of the lanes: the same manifolds, laid out again.
  EXPECT_FALSE(s.step());
  EXPECT_EQ(s.plan().contact_manifolds, 0u);
  s.step();
  EXPECT_TRUE(s.step());
  s.world.set_linear_velocity(s.upper[5], {0.1, 0.0, 0.0});  // wakes stack 5 alone
  EXPECT_FALSE(s.step());
  EXPECT_EQ(s.plan().contact_manifolds, 2u);
}

INSTANTIATE_TEST_SUITE_P(ContactLayout, ContactLayoutKept, ::testing::Values(1, 2),
                         [](const ::testing::TestParamInfo<int>& threads) {
                           return std::to_string(threads.param) + "Threads";
                         });

// The same state, bit for bit, as a world made to colour its contacts every step (a settings
// call counts as a change of its bodies), through steps that keep the layout and steps that
// change it.
TEST(ContactLayout, KeptGivesTheBitsOfColouringAgain) {
  Stacks keeping(2), colouring(2);
  int kept = 0;
  for (int step = 0; step < 40; ++step) {
    const auto change = [&](Stacks& s) {
      return [&s, step](std::vector<ContactManifold>& c) {
        if (step >= 10) c[5].friction = 0.6;
        if (step >= 20) c[2] = between(s, s.lower[0], s.lower[1]);
        if (step >= 30) c[9].point_count = 2;
      };
    };
    kept += keeping.step(change(keeping)) ? 1 : 0;
    colouring.world.set_settings(colouring.world.settings());
    EXPECT_FALSE(colouring.step(change(colouring)));
  }
  EXPECT_GE(kept, 30);
  EXPECT_EQ(keeping.world.state_hash(), colouring.world.state_hash());
}

}  // namespace
}  // namespace softstep::test
