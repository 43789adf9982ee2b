// The accuracy metrics on hand-built states whose answer is known.
#include "softstep/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scenes/chain_scene.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

BodyId add_static(World& world, const Eigen::Vector3d& at) {
  BodyDef def;
  def.type = BodyType::Static;
  def.position = at;
  return world.create_body(def);
}

BodyId add_sphere(World& world, const Eigen::Vector3d& at, double mass) {
  BodyDef def;
  def.position = at;
  def.mass = mass;
  def.inertia = solid_sphere_inertia(mass, 0.1);
  return world.create_body(def);
}

TEST(Metrics, JointErrorsOfJointsPulledApartByKnownDistances) {
  World world;
  const BodyId ground = add_static(world, {0, 0, 0});
  const BodyId a = add_sphere(world, {1, 0, 0}, 1.0);
  const BodyId b = add_sphere(world, {2, 0, 0}, 1.0);
  BallJointDef ball;
  ball.body_a = ground;
  ball.body_b = a;
  ball.local_anchor_a = {1, 0, 0};
  const JointId first = world.create_ball_joint(ball);
  DistanceJointDef rod;
  rod.body_a = a;
  rod.body_b = b;
  rod.rest_length = 1.0;
  const JointId second = world.create_distance_joint(rod);
  const std::vector<JointId> joints{first, second};
  EXPECT_EQ(scenes::joint_errors(world, joints).max, 0.0);
  // Pull a 0.3 m off its anchor (across the rod: its length grows to sqrt(1 + 0.09) m)...
  world.set_position(a, {1, 0.3, 0});
  const double rod_error = std::sqrt(1.09) - 1.0;
  scenes::JointErrors e = scenes::joint_errors(world, joints);
  EXPECT_NEAR(e.max, 0.3, 1e-12);
  EXPECT_NEAR(e.rms, std::sqrt((0.09 + rod_error * rod_error) / 2.0), 1e-12);
  // ... and b 0.4 m further along the rod.
  world.set_position(a, {1, 0, 0});
  world.set_position(b, {2.4, 0, 0});
  e = scenes::joint_errors(world, joints);
  EXPECT_NEAR(e.max, 0.4, 1e-12);
  EXPECT_NEAR(e.rms, std::sqrt(0.16 / 2.0), 1e-12);
}

TEST(Metrics, EnergyOfABodyWithKnownKineticAndPotentialEnergy) {
  World world;  // gravity 9.81 down
  const double mass = 2.0, height = 3.0;
  const BodyId body = add_sphere(world, {0.5, height, -1.0}, mass);
  world.set_linear_velocity(body, {1, 2, 2});   // |v|^2 = 9
  world.set_angular_velocity(body, {0, 0, 5});  // I = 0.4 m r^2 = 0.008
  const std::vector<BodyId> bodies{body};
  const double kinetic = 0.5 * mass * 9.0 + 0.5 * 0.008 * 25.0;
  const double potential = mass * 9.81 * height;
  EXPECT_NEAR(metrics::mechanical_energy(world, bodies, {}), kinetic + potential, 1e-12);

  // A soft ball joint to the world, anchored at the centre (m_eff = m), stretched 0.2 m:
  // it stores 1/2 k x^2 with k = m omega^2. A rigid joint stores nothing.
  const double hertz = 2.0, x = 0.2;
  BallJointDef spring;
  spring.body_a = add_static(world, {0.5, height - x, -1.0});
  spring.body_b = body;
  spring.spring = Spring::soft(hertz, 0.1);
  BallJointDef rigid = spring;
  rigid.spring = Spring::rigid();
  const std::vector<JointId> joints{world.create_ball_joint(spring),
                                    world.create_ball_joint(rigid)};
  const double omega = 2.0 * std::numbers::pi * hertz;
  EXPECT_NEAR(metrics::mechanical_energy(world, bodies, joints),
              kinetic + potential + 0.5 * mass * omega * omega * x * x, 1e-9);
}

TEST(Metrics, StretchAndDriftOfKnownPaths) {
  const std::vector<Eigen::Vector3d> path{{0, 0, 0}, {3, 4, 0}, {3, 4, 2}};
  EXPECT_DOUBLE_EQ(metrics::stretch_ratio(path, 5.0), 7.0 / 5.0);
  World world;
  const std::vector<BodyId> bodies{add_sphere(world, {0, 0, 0}, 1.0),
                                   add_sphere(world, {1, 1, 1}, 1.0)};
  const std::vector<Eigen::Vector3d> reference{{0, 0, 0.3}, {1, 1.4, 1}};
  EXPECT_NEAR(metrics::position_drift(world, bodies, reference), std::sqrt((0.09 + 0.16) / 2.0),
              1e-12);
}

}  // namespace
}  // namespace softstep
