// The pyramid (base 20: 210 boxes, 420 manifolds of Bullet's) is bit-identical at every SIMD
// width this CPU runs and on 1 and 2 threads: state hash and every contact reading, each step.
// Bullet finds the contacts once, from the reference world (scalar, 1 thread); the others
// take the same contacts, which is right only while every world stays identical to it, and
// that is what the hash compares each step.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

#include "contacts/contact_scenes.hpp"
#include "simd_widths.hpp"

namespace softstep::test {
namespace {

// Every reading's bits, in input order.
std::vector<double> reading_values(const World& world) {
  std::vector<double> v;
  for (const ContactReading& r : world.contact_readings()) {
    v.push_back(double(r.point_count));
    for (int k = 0; k < r.point_count; ++k) {
      const ContactPointReading& p = r.points[static_cast<std::size_t>(k)];
      v.insert(v.end(), {p.normal_impulse, p.friction_impulse.x(), p.friction_impulse.y(),
                         p.friction_impulse.z(), p.max_normal_impulse, p.is_new ? 1.0 : 0.0});
    }
    v.insert(v.end(), {r.rolling_impulse.x(), r.rolling_impulse.y(), r.rolling_impulse.z()});
  }
  return v;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(PyramidIdentity, BitIdenticalAcrossWidthsAndThreads) {
  struct Twin {
    std::string name;
    bench::ContactScene scene;
  };
  const auto settings = [](SimdWidth width, int threads) {
    WorldSettings s;
    s.simd = width;
    s.threads = threads;
    s.fixed_threads = true;
    s.sleeping = false;
    return s;
  };
  bench::ContactScene reference = bench::make_pyramid(20, settings(SimdWidth::Scalar, 1));
  std::vector<Twin> twins;
  for (SimdWidth w : kEveryWidth) {
    if (!cpu_runs(w)) continue;
    for (int threads : {1, 2}) {
      if (w == SimdWidth::Scalar && threads == 1) continue;
      twins.push_back({std::string(simd_width_name(w)) + ", " + std::to_string(threads) +
                           " thread(s)",
                       bench::make_pyramid(20, settings(w, threads))});
      twins.back().scene.world->set_profiling(true);  // the step's thread count
    }
  }
  ASSERT_GE(twins.size(), 3u);
  int shared_steps = 0;
  for (int step = 0; step < 60; ++step) {
    const auto& contacts = reference.collision->find(*reference.world, reference.friction,
                                                     reference.restitution);
    ASSERT_GT(contacts.size(), 400u);
    reference.world->step(1.0 / 60.0, contacts);
    const std::uint64_t hash = reference.world->state_hash();
    const std::vector<double> readings = reading_values(*reference.world);
    for (Twin& t : twins) {
      t.scene.world->step(1.0 / 60.0, contacts);
      ASSERT_EQ(t.scene.world->state_hash(), hash) << t.name << " differs at step " << step;
      ASSERT_TRUE(same_bits(reading_values(*t.scene.world), readings))
          << t.name << ": contact readings differ at step " << step;
      shared_steps += t.scene.world->last_step_profile().threads > 1 ? 1 : 0;
    }
  }
  // The two-thread worlds did run on two threads (fixed_threads).
  EXPECT_GT(shared_steps, 0);
}

}  // namespace
}  // namespace softstep::test
