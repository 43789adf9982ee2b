// The weld joint keeps the promises of weld.hpp: rigid, it holds a cantilever as a rigid
// beam; with a soft angular half it is a torsion spring of the given frequency about every
// axis, felt by the effective inertia its rows see.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <ostream>

#include "frame_constants.hpp"
#include "joints/joint_test_support.hpp"
#include "scenes/joint_at.hpp"

namespace softstep {
namespace {

using test::kDt;
using test::kG;
using test::kPi;

// A 1 m beam of 2 kg (1.0 x 0.1 x 0.1 m) welded at one end to a static wall, horizontal,
// under gravity: the weld's rows hold the weight m g and the torque m g L/2.
TEST(Weld, RigidWeldHoldsACantileverLikeARigidBeam) {
  World world;
  const double m = 2.0, length = 1.0;
  const Eigen::Matrix3d inertia = solid_box_inertia(m, {length, 0.1, 0.1});
  const BodyId wall = test::static_body(world);
  const BodyId beam = test::dynamic_body(world, {length / 2, 0.0, 0.0}, m, inertia);
  auto j = scenes::joint_at<WeldJointDef>(world, wall, beam, Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::UnitZ());
  const JointId joint = world.create_joint(j);
  const Eigen::Vector3d tip_local(length / 2, 0.0, 0.0);
  double worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    const BodyState b = world.body(beam);
    const Eigen::Vector3d tip = b.position + b.orientation * tip_local;
    worst = std::max(worst, (tip - Eigen::Vector3d(length, 0.0, 0.0)).norm());
  }
  // Rigid rows are solved as 60 Hz springs (omega_r) and relaxed, each row stiff in
  // proportion to its own effective mass: the angular rows carry the torque m g L/2 on the
  // beam's inertia about its centre, I_zz, and sag theta = (m g L/2) / (I_zz omega_r^2); the
  // point rows carry m g on m_eff = 1 / (1/m + (L/2)^2 / I_zz) (anchored L/2 off the centre)
  // and sag m g / (m_eff omega_r^2). The tip moves L theta plus that; bound: twice the sum
  // (1.4e-3 m on a 1 m beam; unwelded, it would fall 20 m in these 2 s).
  const double omega_r = 2.0 * kPi * 60.0;
  const double theta = m * kG * length / 2 / (inertia(2, 2) * omega_r * omega_r);
  const double m_eff = 1.0 / (1.0 / m + length * length / 4 / inertia(2, 2));
  const double bound = 2.0 * (length * theta + m * kG / (m_eff * omega_r * omega_r));
  EXPECT_LT(worst, bound);
  EXPECT_LT(world.joint_reading(joint).angular_error, 2.0 * theta);
  // The weld carries the weight and the torque (reading: on B, world frame).
  const JointReading r = world.joint_reading(joint);
  EXPECT_NEAR(r.force.y(), m * kG, 0.01 * m * kG);
  EXPECT_NEAR(r.torque.z(), m * kG * length / 2, 0.01 * m * kG * length / 2);
}

struct TorsionCase {
  int axis;  // 0 x, 1 y, 2 z: B's principal axis the oscillation turns about
  double hertz;
};

void PrintTo(const TorsionCase& c, std::ostream* os) {
  *os << "axis " << c.axis << ", " << c.hertz << " Hz";
}

class SoftWeld : public ::testing::TestWithParam<TorsionCase> {};

// A body turning about its own centre on a soft angular weld to a static body, anchored at
// its centre: the angular rows see its inertia I (their effective inertia matrix is I
// itself), so each principal axis oscillates at the weld's frequency, with no gravity and
// no damping. The principal inertias differ fivefold: a solver using one scalar effective
// inertia for all three rows would be off on at least two axes.
TEST_P(SoftWeld, AngularHalfOscillatesAtItsFrequencyAboutEveryAxis) {
  const TorsionCase c = GetParam();
  WorldSettings s;
  s.gravity.setZero();
  s.substeps = 8;
  s.sleeping = false;
  World world(s);
  const BodyId ground = test::static_body(world);
  const BodyId body = test::dynamic_body(world, {0.0, 1.0, 0.0}, 3.0,
                                         Eigen::Vector3d(0.02, 0.05, 0.1).asDiagonal());
  auto j = scenes::joint_at<WeldJointDef>(world, ground, body, {0.0, 1.0, 0.0},
                                          Eigen::Vector3d(1.0, 1.0, 1.0));
  j.angular = Spring::soft(c.hertz, 0.0);
  world.create_joint(j);
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(c.axis);
  world.set_angular_velocity(body, 0.05 * axis);
  const double period = 1.0 / c.hertz;
  double off_axis = 0.0;
  const auto crossings = test::upward_crossings(
      [&] {
        world.step(kDt);
        const Eigen::Vector3d w = world.body(body).angular_velocity;
        off_axis = std::max(off_axis, (w - w.dot(axis) * axis).norm());
      },
      [&] { return world.body(body).angular_velocity.dot(axis); }, kDt,
      static_cast<int>(6.3 * period / kDt));
  ASSERT_GE(crossings.size(), 5u);
  const double measured = 1.0 / test::mean_period(crossings);
  // Implicit Euler turns at atan(omega h) / h: 0.04 % slow at 3 Hz and h = 1/480 s, well
  // inside the 2 % the issue sets.
  EXPECT_NEAR(measured, c.hertz, 0.02 * c.hertz);
  // About a principal axis the other two stay still.
  EXPECT_LT(off_axis, 1e-3 * 0.05);
}

INSTANTIATE_TEST_SUITE_P(PrincipalAxes, SoftWeld,
                         ::testing::Values(TorsionCase{0, 3.0}, TorsionCase{1, 3.0},
                                           TorsionCase{2, 3.0}, TorsionCase{2, 0.5}));

TEST(Weld, JointDefRoundTrips) {
  World world;
  const BodyId a = test::static_body(world);
  const BodyId b = test::dynamic_body(world, {1, 0, 0}, 2.0, Eigen::Matrix3d::Identity() * 0.02);
  WeldJointDef j;
  j.body_a = a;
  j.body_b = b;
  j.frame_a = {{0.5, 0.1, 0.0}, {0.0, 0.0, -3.0}, {2.0, 0.0, 0.0}};
  j.frame_b = {{-0.5, 0.1, 0.0}, {0.0, 0.0, 1.0}, {0.0, 7.0, 0.0}};
  j.linear = Spring::soft(6.0, 0.5);
  j.angular = Spring::soft(2.0, 0.125);
  const WeldJointDef got = world.joint_def<WeldJointDef>(world.create_joint(j));
  EXPECT_EQ(got.body_a, a);
  EXPECT_EQ(got.body_b, b);
  EXPECT_EQ(got.frame_a.local_anchor, j.frame_a.local_anchor);
  EXPECT_TRUE(got.frame_a.local_axis.isApprox(-Eigen::Vector3d::UnitZ(), 1e-15));
  EXPECT_TRUE(got.frame_b.local_reference.isApprox(Eigen::Vector3d::UnitY(), 1e-15));
  EXPECT_EQ(got.linear.hertz, 6.0);
  EXPECT_EQ(got.linear.damping_ratio, 0.5);
  EXPECT_EQ(got.angular.hertz, 2.0);
  EXPECT_EQ(got.angular.damping_ratio, 0.125);
}

// A weld made soft in place lets the cantilever droop, and wakes it.
TEST(Weld, SetJointSoftensTheWeldAndWakes) {
  World world;
  const BodyId wall = test::static_body(world);
  const BodyId beam =
      test::dynamic_body(world, {0.5, 0.0, 0.0}, 2.0, solid_box_inertia(2.0, {1.0, 0.1, 0.1}));
  auto j = scenes::joint_at<WeldJointDef>(world, wall, beam, Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::UnitZ());
  const JointId id = world.create_joint(j);
  for (int i = 0; i < 60; ++i) world.step(kDt);
  ASSERT_FALSE(world.is_awake(beam));
  j.angular = Spring::soft(1.0, 1.0);
  world.set_joint(id, j);
  EXPECT_TRUE(world.is_valid(id));
  EXPECT_TRUE(world.is_awake(beam));
  for (int i = 0; i < 120; ++i) world.step(kDt);
  // A 1 Hz torsion spring holds m g L/2 = 9.81 N m at 9.81 / (I (2 pi)^2) rad: 0.37 rad with
  // I the inertia about the weld (0.668 kg m^2), more with the inertia about the centre
  // (0.168) that the angular rows alone see. Rigid, it was below 1e-3 rad.
  const double droop = world.joint_reading(id).angular_error;
  EXPECT_GT(droop, 0.2);
  EXPECT_LT(droop, kPi / 2);
}

}  // namespace
}  // namespace softstep
