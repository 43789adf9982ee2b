// Contacts give bit-identical results at every SIMD width and thread count (the design's
// promise): stacks, a sliding box, a bouncing ball, rolling balls (round shapes among them:
// radius_a and radius_b) and a pendulum joint in one world, compared by state hash and by
// every reading.
#include <gtest/gtest.h>

#include <cstring>

#include "contacts/analytic_contacts.hpp"
#include "simd_widths.hpp"

namespace softstep::test {
namespace {

struct Outcome {
  std::uint64_t hash;
  std::vector<double> readings;
};

Outcome run(SimdWidth width, int threads) {
  WorldSettings s;
  s.simd = width;
  s.threads = threads;
  s.fixed_threads = true;
  s.sleeping = false;
  s.gravity = {1.5, -9.81, 0.0};  // everything slides a little
  World world(s);
  const BodyId ground = add_ground(world);
  std::vector<std::vector<BodyId>> stacks(12);
  for (std::size_t k = 0; k < stacks.size(); ++k) {
    for (int i = 0; i < 6; ++i) {
      stacks[k].push_back(add_box(world, {3.0 * double(k), 0.5 + i + 0.01 * i, 0.2 * double(k % 3)},
                                  5.0, kUnitCubeHalf));
    }
  }
  BodyDef d;
  d.position = {-3.0, 1.5, 0.0};
  d.mass = 2.0;
  d.inertia = solid_sphere_inertia(2.0, 0.25);
  d.linear_velocity = {0.5, 0.0, 0.3};
  const BodyId ball = world.create_body(d);
  d.position = {-6.0, 0.25, 0.0};
  d.angular_velocity = {0.0, 0.0, -4.0};
  const BodyId roller = world.create_body(d);
  // Round shapes (radius_b, and radius_a with the pair given the other way round), rolling
  // fast enough that their cores' turning within a step matters.
  d.position = {-9.0, 0.25, 0.0};
  d.linear_velocity = {5.0, 0.0, 0.3};
  d.angular_velocity = {0.0, 0.0, -20.0};
  const BodyId round_b = world.create_body(d);
  d.position = {-12.0, 0.25, 1.0};
  d.angular_velocity = {1.0, 0.0, -20.0};
  const BodyId round_a = world.create_body(d);
  BallJointDef j;
  j.body_a = stacks[0].back();
  j.body_b = add_box(world, {0.0, 6.5, 1.5}, 1.0, {0.2, 0.2, 0.2});
  j.local_anchor_a = {0.0, 0.5, 0.5};
  j.local_anchor_b = {0.0, 0.0, -1.0};
  world.create_joint(j);
  Outcome out{};
  for (int step = 0; step < 90; ++step) {
    std::vector<ContactManifold> contacts;
    for (std::size_t k = 0; k < stacks.size(); ++k) {
      contacts.push_back(box_on_ground(world, ground, stacks[k][0], kUnitCubeHalf, 0.0,
                                       0.2 + 0.1 * double(k % 4)));
      for (std::size_t i = 1; i < stacks[k].size(); ++i) {
        contacts.push_back(box_on_box(world, stacks[k][i - 1], stacks[k][i], kUnitCubeHalf));
      }
    }
    ContactManifold b = sphere_on_ground(world, ground, ball, 0.25);
    b.restitution = 0.7;
    b.friction = 0.4;
    contacts.push_back(b);
    ContactManifold r = sphere_on_ground(world, ground, roller, 0.25);
    r.friction = 0.9;
    r.rolling_resistance = 0.02;
    contacts.push_back(r);
    ContactManifold rb = round_sphere_on_ground(world, ground, round_b, 0.25);
    rb.friction = 0.7;
    rb.rolling_resistance = 0.01;
    contacts.push_back(rb);
    ContactManifold ra = round_sphere_on_ground(world, ground, round_a, 0.25, /*ball_is_a=*/true);
    ra.friction = 0.5;
    contacts.push_back(ra);
    world.step(1.0 / 60.0, contacts);
  }
  out.hash = world.state_hash();
  for (const ContactReading& r : world.contact_readings()) {
    for (int k = 0; k < r.point_count; ++k) {
      const auto& p = r.points[static_cast<std::size_t>(k)];
      out.readings.insert(out.readings.end(),
                          {p.normal_impulse, p.friction_impulse.x(), p.friction_impulse.y(),
                           p.friction_impulse.z(), p.max_normal_impulse});
    }
    out.readings.insert(out.readings.end(),
                        {r.rolling_impulse.x(), r.rolling_impulse.y(), r.rolling_impulse.z()});
  }
  return out;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(ContactIdentity, SameBitsAtEveryWidthAndThreadCount) {
  const Outcome base = run(SimdWidth::Scalar, 1);
  ASSERT_FALSE(base.readings.empty());
  int compared = 0;
  for (SimdWidth w : test::kEveryWidth) {
    if (!test::cpu_runs(w)) continue;
    for (int threads : {1, 2}) {
      {
        const Outcome o = run(w, threads);
        EXPECT_EQ(o.hash, base.hash) << simd_width_name(w) << " x" << threads;
        EXPECT_TRUE(bitwise_equal(o.readings, base.readings))
            << simd_width_name(w) << " x" << threads;
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 3);
}

// With the checks on two threads (4,096 manifolds or more) the first thread lays the contacts
// out beside them, before any contact wakes an island; a contact that wakes one makes the step
// lay them out again after the wake. The world of 4,200 resting boxes, asleep, and then a
// contact from a pushed box that wakes its neighbour: the same bits on one thread and two.
struct Woken {
  std::uint64_t hash;
  std::vector<bool> beside;  // per step from the push on: the load ran beside the checks
  std::vector<bool> kept;    // and kept the last step's layout
  bool neighbour_awake;
};

Woken push_a_sleeping_row(int threads) {
  WorldSettings s;
  s.threads = threads;
  s.fixed_threads = true;
  s.time_to_sleep = 0.1;
  World world(s);
  world.set_profiling(true);
  const BodyId ground = add_ground(world);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 4200; ++i) {
    boxes.push_back(add_box(world, {1.5 * i, 0.5, 0.0}, 1.0, kUnitCubeHalf));
  }
  const auto on_ground = [&] {
    std::vector<ContactManifold> c;
    for (BodyId b : boxes) c.push_back(box_on_ground(world, ground, b, kUnitCubeHalf));
    return c;
  };
  for (int i = 0; i < 60 && world.is_awake(boxes[1]); ++i) world.step(1.0 / 60.0, on_ground());
  EXPECT_FALSE(world.is_awake(boxes[1]));
  world.set_linear_velocity(boxes[0], {2.0, 0.0, 0.0});  // wakes box 0 alone
  Woken out{0, {}, {}, false};
  for (int step = 0; step < 5; ++step) {
    std::vector<ContactManifold> c = on_ground();
    // Box 0's right face against box 1's left face: normal +x from 0 (A) to 1 (B).
    const BodyState a = world.body(boxes[0]);
    const BodyState b = world.body(boxes[1]);
    ContactManifold push;
    push.body_a = boxes[0];
    push.body_b = boxes[1];
    push.normal = Eigen::Vector3d::UnitX();
    push.point_count = 4;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d corner{0.5, (k & 1) ? 0.5 : -0.5, (k & 2) ? 0.5 : -0.5};
      ContactPoint& p = push.points[static_cast<std::size_t>(k)];
      p.anchor_a = corner;
      p.anchor_b = {-0.5, corner.y(), corner.z()};
      p.separation = (b.position.x() - 0.5) - (a.position.x() + 0.5);
      p.feature_id = static_cast<std::uint32_t>(k);
    }
    c.push_back(push);
    world.step(1.0 / 60.0, c);
    out.beside.push_back(world.last_step_profile().contact_load_beside_checks);
    out.kept.push_back(world.last_step_profile().contact_layout_kept);
  }
  out.hash = world.state_hash();
  out.neighbour_awake = world.is_awake(boxes[1]);
  return out;
}

TEST(ContactIdentity, AContactThatWakesAnIslandIsLaidOutAfterTheWake) {
  const Woken one = push_a_sleeping_row(1);
  const Woken two = push_a_sleeping_row(2);
  EXPECT_TRUE(one.neighbour_awake);
  EXPECT_EQ(two.hash, one.hash);
  // Every way was taken on two threads: after the wake on the step that woke box 1, beside
  // the checks on the step after it (which found the contacts asking for what they asked for
  // after the wake), then kept on the steps after that. One thread keeps it a step sooner.
  EXPECT_EQ(two.beside, (std::vector<bool>{false, true, false, false, false}));
  EXPECT_EQ(two.kept, (std::vector<bool>{false, false, true, true, true}));
  EXPECT_EQ(one.beside, (std::vector<bool>(5, false)));
  EXPECT_EQ(one.kept, (std::vector<bool>{false, true, true, true, true}));
}

}  // namespace
}  // namespace softstep::test
