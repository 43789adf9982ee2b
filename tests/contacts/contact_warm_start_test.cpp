// Warm starting finds a manifold by its body pair and key however the user presents it: the
// pair given the other way round (impulses on B flip sign), the manifolds in another order
// than the last step's, and after a body's destruction took its own entries out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "contacts/analytic_contacts.hpp"
#include "frame_constants.hpp"

namespace softstep::test {
namespace {

// The same contact seen from the other body: A and B swap, the normal turns, anchors swap.
ContactManifold swapped(const ContactManifold& m) {
  ContactManifold s = m;
  std::swap(s.body_a, s.body_b);
  s.normal = -m.normal;
  for (int k = 0; k < m.point_count; ++k) {
    ContactPoint& p = s.points[static_cast<std::size_t>(k)];
    std::swap(p.anchor_a, p.anchor_b);
  }
  return s;
}

Eigen::Vector3d total_friction(const ContactReading& r) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < r.point_count; ++k) sum += r.points[static_cast<std::size_t>(k)].friction_impulse;
  return sum;
}

// A 10 kg box held by static friction on a 25 degree slope (gravity leaned towards +x, mu 0.6
// > tan 25 degrees). Each sub-step friction carries m g sin(25 degrees) h along -x on the box.
// From the second second on, every other step hands the manifold with A and B swapped: the
// friction reading is then on the ground, +m g sin h along x. A warm start that missed the
// swapped pair would mark the points new; one that kept the sign would start each swapped step
// pushing the box down the slope with twice its friction, and the box would creep.
TEST(ContactWarmStart, SwappedBodyPairIsMatchedWithItsImpulsesTurned) {
  const double angle = 25.0 * std::numbers::pi / 180.0;
  WorldSettings s = settings_without_sleep();
  s.gravity = 9.81 * Eigen::Vector3d(std::sin(angle), -std::cos(angle), 0.0);
  World world(s);
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 10.0, kUnitCubeHalf);
  const double h = kDt / s.substeps;
  const double carried = 10.0 * 9.81 * std::sin(angle) * h;
  double x_at_1s = 0.0;
  for (int i = 1; i <= 120; ++i) {
    const ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf, 0.0, 0.6);
    const bool swap = i > 60 && i % 2 == 0;
    const ContactManifold given = swap ? swapped(m) : m;
    world.step(kDt, {&given, 1});
    if (i == 60) x_at_1s = world.body(box).position.x();
    if (i <= 61) continue;
    const ContactReading& r = world.contact_readings()[0];
    EXPECT_EQ(r.body_b, swap ? ground : box);
    for (int k = 0; k < r.point_count; ++k) {
      EXPECT_FALSE(r.points[static_cast<std::size_t>(k)].is_new) << "step " << i;
    }
    const double on_b = total_friction(r).x();
    EXPECT_NEAR(on_b, swap ? carried : -carried, 0.01 * carried) << "step " << i;
  }
  // The slope test's bound for a box that does not creep (contact_physics_test.cpp).
  EXPECT_LT(std::abs(world.body(box).position.x() - x_at_1s), 1e-6);
}

// A column of boxes on the ground, its manifolds made from the poses.
struct Column {
  World world{settings_without_sleep()};
  BodyId ground;
  std::vector<BodyId> boxes;
  std::vector<ContactManifold> contacts() const {
    std::vector<ContactManifold> out{box_on_ground(world, ground, boxes[0], kUnitCubeHalf)};
    for (std::size_t i = 1; i < boxes.size(); ++i) {
      out.push_back(box_on_box(world, boxes[i - 1], boxes[i], kUnitCubeHalf));
    }
    return out;
  }
};

void build(Column& c, int count, Eigen::Vector3d at) {
  c.ground = add_ground(c.world);
  for (int i = 0; i < count; ++i) {
    c.boxes.push_back(
        add_box(c.world, at + Eigen::Vector3d(0.0, 0.5 + i, 0.0), 10.0, kUnitCubeHalf));
  }
}

// The load each manifold carries in a settled column of `count` boxes: the manifold under box
// i holds the (count - i) boxes above, (count - i) m g h per sub-step (as the stack test).
void expect_warm_started_load(const std::vector<ContactReading>& readings,
                              const std::vector<ContactManifold>& given, const Column& c,
                              double h) {
  for (std::size_t j = 0; j < readings.size(); ++j) {
    const auto below = std::find(c.boxes.begin(), c.boxes.end(), given[j].body_b);
    ASSERT_NE(below, c.boxes.end());
    const auto above = static_cast<double>(c.boxes.end() - below);
    double total = 0.0;
    for (int k = 0; k < readings[j].point_count; ++k) {
      const ContactPointReading& p = readings[j].points[static_cast<std::size_t>(k)];
      EXPECT_FALSE(p.is_new) << "manifold " << j;
      total += p.normal_impulse;
    }
    EXPECT_NEAR(total, above * 10.0 * 9.81 * h, 0.01 * above * 10.0 * 9.81 * h) << "manifold " << j;
  }
}

// The column's manifolds are handed in reverse on every other step: each is found where the
// last step did not put it, and the column stands with the loads warm starting carries.
TEST(ContactWarmStart, ManifoldsInAnotherOrderAreMatched) {
  Column c;
  build(c, 6, Eigen::Vector3d::Zero());
  const double h = kDt / c.world.settings().substeps;
  for (int i = 1; i <= 300; ++i) {
    std::vector<ContactManifold> given = c.contacts();
    if (i % 2 == 0) std::reverse(given.begin(), given.end());
    c.world.step(kDt, given);
    if (i > 240) expect_warm_started_load(c.world.contact_readings(), given, c, h);
  }
  const Eigen::Vector3d top = c.world.body(c.boxes.back()).position;
  EXPECT_LT(std::hypot(top.x(), top.z()), 1e-3);
}

// Two columns on one ground; destroying the top box of the first takes its manifold out of the
// cache, and the entries after it move up. The next step hands the manifolds in reverse, so
// each is found through the index rebuilt by the destruction, not at its old position: the
// second column's manifolds, whose loads did not change, start from and end with the same
// impulses as before (a stale index would hand each the entry of its neighbour, which carries
// a box more or less), and none is new.
TEST(ContactWarmStart, DestroyingABodyKeepsTheOthersMatched) {
  Column first, second;
  build(first, 4, Eigen::Vector3d::Zero());
  second.ground = first.ground;
  for (int i = 0; i < 4; ++i) {
    second.boxes.push_back(
        add_box(first.world, Eigen::Vector3d(3.0, 0.5 + i, 0.0), 10.0, kUnitCubeHalf));
  }
  World& world = first.world;
  const auto both = [&] {
    std::vector<ContactManifold> all = first.contacts();
    all.push_back(box_on_ground(world, second.ground, second.boxes[0], kUnitCubeHalf));
    for (std::size_t i = 1; i < second.boxes.size(); ++i) {
      all.push_back(box_on_box(world, second.boxes[i - 1], second.boxes[i], kUnitCubeHalf));
    }
    return all;
  };
  for (int i = 0; i < 240; ++i) world.step(kDt, both());
  const std::vector<ContactReading> before = world.contact_readings();
  world.destroy_body(first.boxes.back());
  first.boxes.pop_back();
  std::vector<ContactManifold> given = both();
  std::reverse(given.begin(), given.end());
  world.step(kDt, given);
  const std::vector<ContactReading>& after = world.contact_readings();
  ASSERT_EQ(after.size(), 7u);
  for (std::size_t j = 0; j < after.size(); ++j) {
    for (int k = 0; k < after[j].point_count; ++k) {
      EXPECT_FALSE(after[j].points[static_cast<std::size_t>(k)].is_new) << "manifold " << j;
    }
  }
  // The second column's four manifolds: the first four given now, the last four before.
  for (std::size_t j = 0; j < 4; ++j) {
    const ContactReading& now = after[j];
    const ContactReading& then = before[before.size() - 1 - j];
    ASSERT_EQ(now.body_b, then.body_b);
    for (int k = 0; k < now.point_count; ++k) {
      const double p = now.points[static_cast<std::size_t>(k)].normal_impulse;
      EXPECT_NEAR(p, then.points[static_cast<std::size_t>(k)].normal_impulse, 1e-3 * p)
          << "manifold " << j << " point " << k;
    }
  }
}

// With warm starting off, every sub-step starts its contacts from zero impulse, as the joints'
// ClearImpulses stage does for them: a sub-step's accumulated impulse is then what that
// sub-step applied. A box at rest carries its weight, m g h per sub-step, so its readings (the
// last sub-step's impulses) sum to m g h. Impulses carried from the sub-step before without
// being applied again would grow with each sub-step (towards substeps x m g h) and be clamped
// and reported wrongly.
TEST(ContactWarmStart, WithWarmStartOffEverySubStepStartsFromZero) {
  WorldSettings s = settings_without_sleep();
  s.warm_start = false;
  World world(s);
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 100.0, kUnitCubeHalf);
  for (int i = 0; i < 120; ++i) {
    const ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf);
    world.step(kDt, {&m, 1});
  }
  const ContactReading& r = world.contact_readings().at(0);
  double total = 0.0;
  for (int k = 0; k < r.point_count; ++k) total += r.points[static_cast<std::size_t>(k)].normal_impulse;
  const double weight = 100.0 * 9.81 * kDt / s.substeps;
  // Without a warm start one sub-step's solve and relax converge to within a few per cent.
  EXPECT_NEAR(total, weight, 0.05 * weight);
}

// The readings are read out of the warm-start cache when first asked for, not by the step;
// they must still be the step's whatever happens to the cache before they are asked for. Two
// identical worlds step a column; one asks for its readings before the top box is destroyed,
// the other only after (the destruction takes that box's entry out of the cache and moves
// the others up): both see the same readings, bit for bit, the dead box's manifold included.
TEST(ContactWarmStart, ReadingsAskedAfterADestructionAreTheSteps) {
  Column asked_before, asked_after;
  build(asked_before, 4, Eigen::Vector3d::Zero());
  build(asked_after, 4, Eigen::Vector3d::Zero());
  for (int i = 0; i < 30; ++i) {
    asked_before.world.step(kDt, asked_before.contacts());
    asked_after.world.step(kDt, asked_after.contacts());
  }
  const std::vector<ContactReading> before = asked_before.world.contact_readings();
  asked_before.world.destroy_body(asked_before.boxes.back());
  asked_after.world.destroy_body(asked_after.boxes.back());
  const std::vector<ContactReading>& after = asked_after.world.contact_readings();
  ASSERT_EQ(before.size(), 4u);
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(after.back().body_b, asked_after.boxes.back());  // the dead box's manifold
  for (std::size_t j = 0; j < before.size(); ++j) {
    EXPECT_EQ(after[j].body_a, before[j].body_a) << "manifold " << j;
    EXPECT_EQ(after[j].body_b, before[j].body_b) << "manifold " << j;
    ASSERT_EQ(after[j].point_count, before[j].point_count) << "manifold " << j;
    for (int k = 0; k < before[j].point_count; ++k) {
      const auto p = static_cast<std::size_t>(k);
      EXPECT_EQ(after[j].points[p].normal_impulse, before[j].points[p].normal_impulse);
      EXPECT_EQ(after[j].points[p].friction_impulse, before[j].points[p].friction_impulse);
      EXPECT_EQ(after[j].points[p].is_new, before[j].points[p].is_new);
      EXPECT_GT(before[j].points[p].normal_impulse, 0.0) << "manifold " << j;
    }
  }
  EXPECT_EQ(asked_before.world.contact_readings().size(), before.size());
}

}  // namespace
}  // namespace softstep::test
