// The wheel and motor joints land on the same state, bit for bit, at every SIMD width and on
// 1 and 2 threads (DESIGN.md: "make that a test, not a hope"): 320 cars (steered, motored,
// sprung, limited wheel joints) driving on the ground through the scene's contacts (1,280
// wheel-ground manifolds with friction, in the same step as the joints), and boxes dragged by
// rigid and soft motor joints, more than 4,096 bodies and joints so a step is shared between
// threads.
// Every third car's suspension, and half of a set of sprung hinges and sliders, are springs
// in absolute units, in the same lane groups as relative ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "scenes/joint_at.hpp"
#include "scenes/vehicle_scene.hpp"
#include "simd_widths.hpp"

namespace softstep {
namespace {

void add_dragged_boxes(World& world, int count) {
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId g = world.create_body(ground);
  for (int i = 0; i < count; ++i) {
    BodyDef box;
    box.position = {0.3 * i, 5.0, -3.0};
    box.angular_velocity = {0.1 * (i % 7), 0.0, 0.2};
    const BodyId b = world.create_body(box);
    MotorJointDef m;
    m.body_a = g;
    m.body_b = b;
    m.frame_a.local_anchor = {0.3 * i + 0.5, 6.0, -3.0};
    m.frame_a.local_axis = {0.0, 1.0, 0.1 * (i % 5)};
    m.frame_b.local_anchor = {0.05, 0.0, 0.0};
    m.max_force = 5.0 + i % 13;
    m.max_torque = 1.0 + i % 3;
    if (i % 2 == 1) m.linear = Spring::soft(2.0, 0.8);
    if (i % 3 == 2) m.angular = Spring::soft(1.5, 1.0);
    world.create_joint(m);
  }
}

// Boxes on revolute and prismatic joints from the ground whose springs alternate between
// relative and absolute units in the same lane groups (the kernel's per-lane select).
void add_sprung_sliders_and_hinges(World& world, BodyId g, int count) {
  for (int i = 0; i < count; ++i) {
    BodyDef box;
    box.position = {0.4 * i, 8.0, 5.0};
    box.angular_velocity = {0.0, 0.3, 0.1 * (i % 5)};
    box.linear_velocity = {0.2 * (i % 3), 0.0, 0.0};
    const BodyId b = world.create_body(box);
    const Eigen::Vector3d at(0.4 * i + 0.1, 8.2, 5.0);
    const Spring spring = i % 2 == 0 ? Spring::absolute(20.0 + i, 0.5 * (i % 3))
                                     : Spring::soft(2.0 + 0.1 * i, 0.3);
    if (i % 4 < 2) {
      RevoluteJointDef r = scenes::joint_at<RevoluteJointDef>(world, g, b, at, {0.2, 1.0, 0.0});
      r.spring = {spring, 0.1};
      world.create_joint(r);
    } else {
      PrismaticJointDef p =
          scenes::joint_at<PrismaticJointDef>(world, g, b, at, {1.0, 0.0, 0.3});
      p.spring = {spring, -0.05};
      world.create_joint(p);
    }
  }
}

struct CarsRun {
  std::uint64_t hash = 0;
  int shared_steps = 0;
  double lowest_chassis = 0.0;  // m, the lowest chassis centre at the end
};

CarsRun run(SimdWidth width, int threads) {
  WorldSettings s;
  s.simd = width;
  s.threads = threads;
  auto world = std::make_unique<World>(s);
  world->set_profiling(true);
  scenes::VehicleOptions cars;
  cars.cars = 320;
  cars.steering = 0.05;
  cars.absolute_every = 3;  // every third car's suspension in N/m, in groups with relative ones
  const scenes::VehicleScene scene = scenes::build_vehicle(*world, cars);
  add_dragged_boxes(*world, 64);
  add_sprung_sliders_and_hinges(*world, scene.ground, 64);
  CarsRun r;
  std::vector<ContactManifold> contacts;
  for (int i = 0; i < 130; ++i) {  // past the adaptive thread count's first probe
    scenes::vehicle_contacts(*world, scene, contacts);
    world->step(1.0 / 60.0, contacts);
    r.shared_steps += world->last_step_profile().threads > 1 ? 1 : 0;
  }
  r.hash = world->state_hash();
  r.lowest_chassis = 1e9;
  for (const scenes::Car& car : scene.cars)
    r.lowest_chassis = std::min(r.lowest_chassis, world->body(car.chassis).position.y());
  return r;
}

TEST(VehicleAndMotorJoints, BitIdenticalAcrossWidthsAndThreads) {
  const CarsRun reference = run(SimdWidth::Scalar, 1);
  // The contacts carry the cars: every chassis still rides above its axles' height (0.35 m;
  // it rests near 0.58 m), none fell through the ground.
  EXPECT_GT(reference.lowest_chassis, 0.45);
  int compared = 0;
  for (SimdWidth w : test::kEveryWidth) {
    if (!test::cpu_runs(w)) continue;
    for (int threads : {1, 2}) {
      const CarsRun r = run(w, threads);
      ++compared;
      EXPECT_EQ(r.hash, reference.hash) << simd_width_name(w) << ", " << threads << " thread(s)";
      if (threads > 1 && std::thread::hardware_concurrency() > 1) {
        EXPECT_GE(r.shared_steps, 2) << "never ran on two threads";
      }
    }
  }
  EXPECT_GE(compared, 4) << "fewer than two widths compared";
}

}  // namespace
}  // namespace softstep
