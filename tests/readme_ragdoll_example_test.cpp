// The README's ragdoll example ("Ragdolls"), cut out of README.md at configure time
// (tests/CMakeLists.txt) and compiled here, so that the README's code cannot rot: it builds a
// shoulder and an elbow between three bodies of an arm and reads the shoulder back.
#include <gtest/gtest.h>

#include <cstdio>

#include "scenes/joint_at.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

TEST(Readme, RagdollExampleBuildsAShoulderAndAnElbow) {
  World world;
  const auto box = [&](const Eigen::Vector3d& at, double mass, BodyType type) {
    BodyDef d;
    d.type = type;
    d.position = at;
    d.mass = mass;
    d.inertia = Eigen::Matrix3d::Identity() * 0.01;
    return world.create_body(d);
  };
  const BodyId chest = box({0.0, 0.0, 0.0}, 10.0, BodyType::Static);
  const BodyId upper_arm = box({0.35, 0.0, 0.0}, 2.0, BodyType::Dynamic);
  const BodyId forearm = box({0.62, 0.0, 0.0}, 1.5, BodyType::Dynamic);
  const Eigen::Vector3d shoulder_point(0.22, 0.0, 0.0), elbow_point(0.48, 0.0, 0.0);
  {
#include "readme_examples/ragdoll_example.inc"
  }
  ASSERT_EQ(world.joint_count(), 2u);
  const auto shoulder = world.joint_def<SwingTwistJointDef>(world.joint_ids().front());
  EXPECT_EQ(shoulder.cone.half_angle_x, 1.3);
  EXPECT_TRUE(shoulder.motor.enabled);
  // Let the arm fall for 2 s: it hangs in its cone (half_angle_x = 1.3 rad up and down).
  for (int i = 0; i < 120; ++i) world.step(1.0 / 60.0);
  const JointReading r = world.joint_reading(world.joint_ids().front());
  EXPECT_GT(r.swing, 0.5);
  EXPECT_LT(r.angular_error, 0.02);
}

}  // namespace
}  // namespace softstep
