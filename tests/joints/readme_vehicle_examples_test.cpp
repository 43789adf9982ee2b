// The README's wheel, motor-joint and bridge examples ("Cars, bridges, dragging"), cut out of README.md at
// configure time (tests/CMakeLists.txt) and compiled here, so that the README's code cannot rot.
// Each runs in a small world and is held to what the README says it does.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

using test::kDt;

BodyId box(World& world, const Eigen::Vector3d& at, double mass, BodyType type) {
  BodyDef d;
  d.type = type;
  d.position = at;
  d.mass = mass;
  d.inertia = solid_box_inertia(mass, {0.4, 0.4, 0.4});
  return world.create_body(d);
}

// The wheel hangs under a fixed chassis (a kinematic body at rest, so only the wheel moves): the
// motor spins it up to 30 rad/s about the axle turned by the steering, and the spring holds it
// within the travel limits.
TEST(Readme, WheelExampleDrivesAndSteersTheWheel) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  const BodyId chassis = box(world, {0.0, 0.5, 0.0}, 1200.0, BodyType::Kinematic);
  const Eigen::Vector3d wheel_centre(1.3, 0.0, 0.8);
  BodyDef wheel_def;
  wheel_def.position = wheel_centre;
  wheel_def.mass = 20.0;
  wheel_def.inertia = solid_sphere_inertia(20.0, 0.35);
  const BodyId wheel = world.create_body(wheel_def);
  {
#include "readme_examples/wheel_example.inc"
  } ASSERT_EQ(world.joint_count(), 1u);
  EXPECT_EQ(world.joint_def<WheelJointDef>(world.joint_ids().front()).steering, 0.2);
  for (int i = 0; i < 180; ++i) world.step(kDt);  // 3 s: 200 N m spin 0.98 kg m^2 up in 0.15 s
  const BodyState w = world.body(wheel);
  // The axle (z) turned by the steering about the suspension axis (y).
  const Eigen::Vector3d axle =
      Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::abs(w.angular_velocity.dot(axle)), 30.0, 0.3);
  EXPECT_LT((w.angular_velocity - w.angular_velocity.dot(axle) * axle).norm(), 0.05);
  // Hanging on the spring: 20 kg on k = 300 kg (2 pi 2 Hz)^2 sags 4.1 mm, well inside +-0.25 m.
  const double travel = (w.position - wheel_centre).dot(Eigen::Vector3d::UnitY());
  EXPECT_LT(travel, 0.0);
  EXPECT_GT(travel, -0.25);
}

// The dragged body follows the mouse with a force of at most 500 N: it gets there, and never
// faster than a 500 N pull allows.
TEST(Readme, MotorExampleDragsABodyToTheMouse) {
  WorldSettings settings;
  settings.gravity = Eigen::Vector3d::Zero();
  settings.sleeping = false;
  World world(settings);
  const BodyId ground = box(world, {0.0, 0.0, 0.0}, 1.0, BodyType::Static);
  const BodyId grabbed = box(world, {2.0, 0.0, 0.0}, 10.0, BodyType::Dynamic);
  const Eigen::Vector3d mouse_point(2.2, 0.0, 0.0);      // where the user clicked on the body
  const Eigen::Vector3d new_mouse_point(4.2, 0.0, 0.0);  // where the mouse went, 2 m on
  {
#include "readme_examples/motor_example.inc"
  } ASSERT_EQ(world.joint_count(), 1u);
  double fastest = 0.0;
  for (int i = 0; i < 300; ++i) {
    world.step(kDt);
    fastest = std::max(fastest, world.body(grabbed).linear_velocity.norm());
  }
  // 5 s later the grabbed point is at the mouse (a 5 Hz spring at ratio 0.7 settles in ~0.3 s).
  const BodyState b = world.body(grabbed);
  const Eigen::Vector3d grabbed_point = b.position + b.orientation * Eigen::Vector3d(0.2, 0.0, 0.0);
  EXPECT_LT((grabbed_point - new_mouse_point).norm(), 1e-3);
  // 500 N on 10 kg over at most 2 m: no faster than sqrt(2 a d) = sqrt(2 * 50 * 2) = 14.1 m/s.
  EXPECT_LT(fastest, std::sqrt(2.0 * 50.0 * 2.0));
  EXPECT_GT(fastest, 0.5);
}

// The bridge hangs from its ropes: each plank is held at its centre, so the ropes carry the
// whole deck (16 x 20 kg x 9.81 = 3,139 N; the hinges and piers only what the ropes' and hinges'
// own compliance shares out, a few percent) and the deck stays level at the piers' height.
TEST(Readme, BridgeExampleHangsTheDeckFromItsRopes) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  {
#include "frame_constants.hpp"
#include "readme_examples/bridge_example.inc"
    ASSERT_EQ(ropes.size(), 16u);
    for (int i = 0; i < 180; ++i) world.step(kDt);
    double carried = 0.0;
    for (const JointId rope : ropes) {
      const double up = world.joint_reading(rope).force.y();
      EXPECT_GT(up, 0.5 * 20.0 * 9.81);  // no rope slack: each holds its plank
      carried += up;
    }
    EXPECT_NEAR(carried, 16 * 20.0 * 9.81, 0.05 * 16 * 20.0 * 9.81);
  }
  for (const BodyId id : world.body_ids()) {
    if (world.body(id).type != BodyType::Dynamic) continue;
    EXPECT_NEAR(world.body(id).position.y(), 0.0, 0.01);
  }
}

}  // namespace
}  // namespace softstep
