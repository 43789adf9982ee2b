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

const Eigen::Vector3d kHalf(0.5, 0.5, 0.5);

struct Scene {
  World world;
  BodyId ground, box, other;
  ContactManifold valid;
};

Scene make_scene() {
  Scene s{World(), {}, {}, {}, {}};
  s.ground = add_ground(s.world);
  s.box = add_box(s.world, {0.0, 0.5, 0.0}, 1.0, kHalf);
  s.other = add_box(s.world, {3.0, 0.5, 0.0}, 1.0, kHalf);
  s.valid = box_on_ground(s.world, s.ground, s.box, kHalf);
  s.world.step(1.0 / 60.0, {&s.valid, 1});  // some warm-start state and readings to keep
  return s;
}

void expect_rejected(const std::function<void(ContactManifold&, Scene&)>& spoil,
                     const std::string& field, const std::string& value) {
  Scene s = make_scene();
  std::vector<ContactManifold> contacts{box_on_ground(s.world, s.ground, s.box, kHalf)};
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
        const BodyId gone = add_box(s.world, {9.0, 0.5, 0.0}, 1.0, kHalf);
        s.world.destroy_body(gone);
        m.body_b = gone;
      },
      "contacts[0].body_b", "BodyId{");
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
