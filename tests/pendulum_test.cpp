// A rigid pendulum swings with the small-angle period of its analytic solution.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "frame_constants.hpp"
#include "softstep/analytic.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

using test::kG;

// Period from the times at which x changes sign going the same way, over several periods.
double measure_period(World& world, BodyId bob, double dt, int steps) {
  std::vector<double> crossings;
  double previous_x = world.body(bob).position.x();
  for (int i = 1; i <= steps; ++i) {
    world.step(dt);
    const double x = world.body(bob).position.x();
    if (previous_x < 0.0 && x >= 0.0) {
      // linear interpolation inside the step
      crossings.push_back((i - 1 + previous_x / (previous_x - x)) * dt);
    }
    previous_x = x;
  }
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

struct Pendulum {
  World world;
  BodyId bob;
};

Pendulum make_pendulum(bool ball_joint, double length, double angle, double radius) {
  WorldSettings s;
  s.gravity = {0.0, -kG, 0.0};
  Pendulum p{World(s), {}};
  BodyDef pivot;
  pivot.type = BodyType::Static;
  const BodyId ground = p.world.create_body(pivot);
  BodyDef bob;
  bob.position = {length * std::sin(angle), -length * std::cos(angle), 0.0};
  bob.mass = 1.0;
  bob.inertia = solid_sphere_inertia(1.0, radius);
  p.bob = p.world.create_body(bob);
  if (ball_joint) {
    BallJointDef j;
    j.body_a = ground;
    j.body_b = p.bob;
    j.local_anchor_b = p.world.local_point(p.bob, Eigen::Vector3d::Zero());
    p.world.create_ball_joint(j);
  } else {
    DistanceJointDef j;
    j.body_a = ground;
    j.body_b = p.bob;
    j.rest_length = length;
    p.world.create_distance_joint(j);
  }
  return p;
}

TEST(Pendulum, DistanceJointPointMassPeriodWithinOnePercent) {
  const double length = 1.0, angle = 5.0 * std::numbers::pi / 180.0;
  Pendulum p = make_pendulum(false, length, angle, 0.05);
  // Anchored at the centre of mass, the bob's spin does not couple: a point pendulum.
  const double expected =
      2.0 * std::numbers::pi / analytic::small_angle_pendulum_frequency(1.0, length, 0.0, kG);
  const double measured = measure_period(p.world, p.bob, 1.0 / 60.0, 60 * 12);
  EXPECT_NEAR(measured, expected, 0.01 * expected);
}

TEST(Pendulum, BallJointPhysicalPendulumPeriodWithinOnePercent) {
  const double length = 1.0, radius = 0.2, angle = 5.0 * std::numbers::pi / 180.0;
  Pendulum p = make_pendulum(true, length, angle, radius);
  // Hinged at a point `length` from the centre: a physical pendulum.
  const double expected =
      2.0 * std::numbers::pi /
      analytic::small_angle_pendulum_frequency(1.0, length, 0.4 * radius * radius, kG);
  const double measured = measure_period(p.world, p.bob, 1.0 / 60.0, 60 * 12);
  EXPECT_NEAR(measured, expected, 0.01 * expected);
}

}  // namespace
}  // namespace softstep
