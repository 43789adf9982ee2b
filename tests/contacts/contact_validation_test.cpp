// Every field of a manifold is checked before the step changes anything: the error names the
// field and the value, and the world (bodies, and the contacts' warm-start state and readings)
// is as it was.
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "contacts/analytic_contacts.hpp"
#include "expect_invalid_argument.hpp"

namespace softstep::test {
namespace {

struct Scene {
  World world;
  BodyId ground, box, other;
  ContactManifold valid;
};

Scene make_scene() {
  Scene s{World(), {}, {}, {}, {}};
  s.ground = add_ground(s.world);
  s.box = add_box(s.world, {0.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  s.other = add_box(s.world, {3.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  s.valid = box_on_ground(s.world, s.ground, s.box, kUnitCubeHalf);
  s.world.step(1.0 / 60.0, {&s.valid, 1});  // some warm-start state and readings to keep
  return s;
}

void expect_rejected(const std::function<void(ContactManifold&, Scene&)>& spoil,
                     const std::string& field, const std::string& value) {
  Scene s = make_scene();
  std::vector<ContactManifold> contacts{box_on_ground(s.world, s.ground, s.box, kUnitCubeHalf)};
  spoil(contacts[0], s);
  const std::uint64_t before = s.world.state_hash();
  const std::vector<ContactReading> readings = s.world.contact_readings();
  expect_invalid_argument([&] { s.world.step(1.0 / 60.0, contacts); }, field, value);
  EXPECT_EQ(s.world.state_hash(), before) << field;
  ASSERT_EQ(s.world.contact_readings().size(), readings.size());
  EXPECT_EQ(s.world.contact_readings()[0].points[0].normal_impulse,
            readings[0].points[0].normal_impulse);
  // And the next valid step warm starts from the kept impulses.
  s.world.step(1.0 / 60.0, {&s.valid, 1});
  EXPECT_FALSE(s.world.contact_readings()[0].points[0].is_new) << field;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(ContactValidation, UnknownAndDestroyedBodies) {
  expect_rejected([](ContactManifold& m, Scene&) { m.body_a = BodyId{77, 0}; },
                  "contacts[0].body_a", "BodyId{77");
  expect_rejected(
      [](ContactManifold& m, Scene& s) {
        const BodyId gone = add_box(s.world, {9.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
        s.world.destroy_body(gone);
        m.body_b = gone;
      },
      "contacts[0].body_b", "BodyId{");
  // Its slot taken by a new body: the old id (one generation behind) is still refused.
  expect_rejected(
      [](ContactManifold& m, Scene& s) {
        const BodyId gone = add_box(s.world, {9.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
        s.world.destroy_body(gone);
        const BodyId reborn = add_box(s.world, {9.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
        ASSERT_EQ(reborn.index, gone.index);
        m.body_a = gone;
      },
      "contacts[0].body_a", "BodyId{");
}

TEST(ContactValidation, BodyAgainstItself) {
  expect_rejected([](ContactManifold& m, Scene& s) { m.body_a = s.box; }, "contacts[0].body_b",
                  "BodyId{");
}

TEST(ContactValidation, Normal) {
  expect_rejected([](ContactManifold& m, Scene&) { m.normal = {0.0, 2.0, 0.0}; },
                  "contacts[0].normal", "(0, 2, 0)");
  expect_rejected([](ContactManifold& m, Scene&) { m.normal = {kNaN, 1.0, 0.0}; },
                  "contacts[0].normal", "nan");
}

TEST(ContactValidation, PointCount) {
  expect_rejected([](ContactManifold& m, Scene&) { m.point_count = 5; },
                  "contacts[0].point_count", "5");
  expect_rejected([](ContactManifold& m, Scene&) { m.point_count = 0; },
                  "contacts[0].point_count", "0");
}

TEST(ContactValidation, Coefficients) {
  expect_rejected([](ContactManifold& m, Scene&) { m.friction = -0.1; }, "contacts[0].friction",
                  "-0.1");
  expect_rejected([](ContactManifold& m, Scene&) { m.restitution = 1.5; },
                  "contacts[0].restitution", "1.5");
  expect_rejected([](ContactManifold& m, Scene&) { m.rolling_resistance = kInf; },
                  "contacts[0].rolling_resistance", "inf");
  expect_rejected([](ContactManifold& m, Scene&) { m.tangent_speed.y() = kNaN; },
                  "contacts[0].tangent_speed.y", "nan");
}

TEST(ContactValidation, Radii) {
  expect_rejected([](ContactManifold& m, Scene&) { m.radius_a = kNaN; }, "contacts[0].radius_a",
                  "nan");
  expect_rejected([](ContactManifold& m, Scene&) { m.radius_b = -0.25; },
                  "contacts[0].radius_b", "-0.25");
  expect_rejected([](ContactManifold& m, Scene&) { m.radius_b = kInf; }, "contacts[0].radius_b",
                  "inf");
  expect_rejected([](ContactManifold& m, Scene&) { m.radius_a = -kInf; },
                  "contacts[0].radius_a", "-inf");
}

TEST(ContactValidation, Points) {
  expect_rejected([](ContactManifold& m, Scene&) { m.points[2].separation = kNaN; },
                  "contacts[0].points[2].separation", "nan");
  expect_rejected([](ContactManifold& m, Scene&) { m.points[1].anchor_a.x() = kInf; },
                  "contacts[0].points[1].anchor_a", "inf");
  expect_rejected([](ContactManifold& m, Scene&) { m.points[3].anchor_b.z() = kNaN; },
                  "contacts[0].points[3].anchor_b", "nan");
  // Finite but outside the float envelope (+-1e9 m), as finite() rules for every other anchor.
  expect_rejected([](ContactManifold& m, Scene&) { m.points[0].anchor_b.y() = 2e9; },
                  "contacts[0].points[0].anchor_b", "2e+09");
  expect_rejected([](ContactManifold& m, Scene&) { m.points[3].feature_id = m.points[0].feature_id; },
                  "contacts[0].points[3].feature_id", "");
}

TEST(ContactValidation, SecondManifoldOfTheSamePairAndKey) {
  Scene s = make_scene();
  const std::uint64_t before = s.world.state_hash();
  std::vector<ContactManifold> contacts{s.valid, s.valid};
  expect_invalid_argument([&] { s.world.step(1.0 / 60.0, contacts); }, "contacts[1].key", "0");
  EXPECT_EQ(s.world.state_hash(), before);
  contacts[1].key = 1;  // another shape pair of the same bodies is fine
  EXPECT_NO_THROW(s.world.step(1.0 / 60.0, contacts));
}

// The checks and the comparison of the keys with last step's run in one pass, in chunks that
// the step's threads take in turn (5,000 manifolds: shared from 4,096), each stopping at its
// first broken manifold: the error must still name the first broken one in input order (a
// repeated key included), and the warm-start index must be right whatever the order.
struct ManyBoxes {
  static constexpr int kBoxes = 5000;
  World world;
  BodyId ground;
  std::vector<BodyId> boxes;
  explicit ManyBoxes(const WorldSettings& settings = {}) : world(settings) {
    ground = add_ground(world);
    for (int i = 0; i < kBoxes; ++i) {
      // Masses that differ, so that each manifold's impulses are its own.
      boxes.push_back(add_box(world, {2.0 * i, 0.5, 0.0}, 1.0 + i % 7, kUnitCubeHalf));
    }
  }
  // Feature ids of their own per box, so that a manifold matched with another box's entry
  // finds no twin for its points.
  std::vector<ContactManifold> contacts() const {
    std::vector<ContactManifold> c;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      c.push_back(box_on_ground(world, ground, boxes[i], kUnitCubeHalf));
      for (int k = 0; k < c.back().point_count; ++k)
        c.back().points[static_cast<std::size_t>(k)].feature_id =
            4 * i + static_cast<std::uint32_t>(k);
    }
    return c;
  }
};

class ManyManifolds : public ::testing::TestWithParam<int> {};  // the step's threads

TEST_P(ManyManifolds, NameTheFirstBrokenOne) {
  WorldSettings settings;
  settings.threads = GetParam();
  settings.fixed_threads = true;
  ManyBoxes s(settings);
  s.world.set_profiling(true);
  s.world.step(1.0 / 60.0, s.contacts());
  // The scan ran on the step's threads (the result below is the same either way).
  EXPECT_EQ(s.world.last_step_profile().check_threads, GetParam());
  const std::uint64_t before = s.world.state_hash();
  const auto expect_named = [&](const std::function<void(std::vector<ContactManifold>&)>& spoil,
                                const std::string& field, const std::string& value) {
    std::vector<ContactManifold> c = s.contacts();
    spoil(c);
    expect_invalid_argument([&] { s.world.step(1.0 / 60.0, c); }, field, value);
    EXPECT_EQ(s.world.state_hash(), before) << field;
  };
  // On two threads the contacts are laid out beside the checks, before any manifold is
  // checked: an unknown body (its index past every slot) and a point count out of range must
  // leave them laid out from nothing (ASan would see a read or write past the arrays).
  expect_named(
      [](auto& c) {
        c[4000].body_b = BodyId{1'000'000, 0};
      },
      "contacts[4000].body_b", "BodyId{1000000");
  expect_named([](auto& c) { c[4000].point_count = 9; }, "contacts[4000].point_count", "9");
  expect_named([](auto& c) { c[4000].point_count = -1; }, "contacts[4000].point_count", "-1");
  // Two broken manifolds in one chunk of the scan, and in chunks far apart (taken by
  // different threads when there are two).
  expect_named(
      [](auto& c) {
        c[1010].radius_a = -1.0;
        c[1000].friction = -1.0;
      },
      "contacts[1000].friction", "-1");
  expect_named(
      [](auto& c) {
        c[4999].radius_a = -1.0;
        c[10].points[0].anchor_b.x() = kInf;
      },
      "contacts[10].points[0].anchor_b", "inf");
  expect_named([](auto& c) { c[4900].points[1].separation = kNaN; },
               "contacts[4900].points[1].separation", "nan");
  expect_named(
      [](auto& c) {
        c[4900].points[1].separation = kNaN;
        c[1000].friction = -1.0;
      },
      "contacts[1000].friction", "-1");
  // A repeated key before a broken manifold is named first, after one it is not; a manifold
  // that both repeats a key and breaks a rule is named for the rule.
  expect_named(
      [&](auto& c) {
        c[3000].body_b = s.boxes[2999];
        c[4900].points[1].separation = kNaN;
      },
      "contacts[3000].key", "0");
  expect_named(
      [&](auto& c) {
        c[3000].body_b = s.boxes[2999];
        c[2000].restitution = 2.0;
      },
      "contacts[2000].restitution", "2");
  expect_named(
      [&](auto& c) {
        c[3000].body_b = s.boxes[2999];
        c[3000].normal.y() = 2.0;
      },
      "contacts[3000].normal", "");
  // The contacts laid out beside the checks of a step that failed are not the plan's: a plan
  // rebuilt after it (a new body) still shows the last good step's.
  {
    std::vector<ContactManifold> c = s.contacts();
    c.resize(4500);
    c[4400].friction = -1.0;
    expect_invalid_argument([&] { s.world.step(1.0 / 60.0, c); }, "contacts[4400].friction", "-1");
    add_box(s.world, {-5.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
    EXPECT_EQ(s.world.step_plan().contact_manifolds, 5000u);
  }
  // And the world steps on from its kept warm start.
  EXPECT_NO_THROW(s.world.step(1.0 / 60.0, s.contacts()));
}

std::string threads_name(const ::testing::TestParamInfo<int>& param) {
  return std::to_string(param.param) + "Threads";
}
INSTANTIATE_TEST_SUITE_P(ContactValidation, ManyManifolds, ::testing::Values(1, 2), threads_name);

TEST(ContactValidation, FewManifoldsAreCheckedOnTheCallersThread) {
  WorldSettings settings;
  settings.threads = 2;
  settings.fixed_threads = true;
  Scene s{World(settings), {}, {}, {}, {}};
  s.ground = add_ground(s.world);
  s.box = add_box(s.world, {0.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  const ContactManifold m = box_on_ground(s.world, s.ground, s.box, kUnitCubeHalf);
  s.world.set_profiling(true);
  s.world.step(1.0 / 60.0, {&m, 1});
  EXPECT_EQ(s.world.last_step_profile().check_threads, 1);
}

TEST(ContactValidation, ManifoldsThatChangeOrderAreWarmStartedFromTheirOwnImpulses) {
  // A key index kept from a step whose order differed would match a moved manifold with its
  // neighbour's entry, whose feature ids are not its points': they would start anew. And as
  // each box touches only the static ground, its solve does not depend on where it sits in
  // the input: the world given the manifolds in orders that change stays bit for bit the
  // world given them in one order.
  ManyBoxes steady, shuffled;
  const std::vector<ContactManifold> first = steady.contacts();
  steady.world.step(1.0 / 60.0, first);
  shuffled.world.step(1.0 / 60.0, first);
  for (int round = 0; round < 3; ++round) {
    for (const std::size_t moved : {std::size_t{4000}, std::size_t{10}, std::size_t{4998}}) {
      for (const bool swap : {false, true}) {
        std::vector<ContactManifold> c = steady.contacts();
        steady.world.step(1.0 / 60.0, c);
        if (swap) std::swap(c[moved], c[moved + 1]);
        shuffled.world.step(1.0 / 60.0, c);
        ASSERT_EQ(steady.world.state_hash(), shuffled.world.state_hash())
            << "round " << round << ", manifold " << moved << (swap ? " swapped" : "");
        const std::vector<ContactReading>& readings = shuffled.world.contact_readings();
        for (std::size_t i = 0; i < readings.size(); ++i) {
          for (const ContactPointReading& p : readings[i].points) {
            ASSERT_FALSE(p.is_new) << "round " << round << ", manifold " << i << " at " << moved
                                   << (swap ? " swapped" : "");
          }
        }
      }
    }
  }
}

TEST(ContactValidation, Settings) {
  WorldSettings bad;
  bad.contact.hertz = 0.0;
  expect_invalid_argument([&] { World w(bad); }, "WorldSettings.contact.hertz", "0");
  bad = {};
  bad.contact.max_push_out_speed = kNaN;
  expect_invalid_argument([&] { World w(bad); }, "WorldSettings.contact.max_push_out_speed",
                          "nan");
}

}  // namespace
}  // namespace softstep::test
