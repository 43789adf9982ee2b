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

}  // namespace
}  // namespace softstep::test
