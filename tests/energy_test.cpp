// An undamped soft oscillator never gains energy: the soft constraint is implicit Euler in
// disguise (talk 2:3:2), which only ever removes energy.
#include <gtest/gtest.h>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

TEST(Energy, UndampedSoftOscillatorNeverGainsEnergy) {
  for (double hertz : {0.5, 2.0, 30.0}) {
    WorldSettings s;
    s.gravity.setZero();
    s.substeps = 4;
    World world(s);
    BodyDef ground;
    ground.type = BodyType::Static;
    const BodyId anchor = world.create_body(ground);
    BodyDef body;
    body.position = {0.3, -0.2, 0.1};
    body.linear_velocity = {0.0, 1.0, 0.0};
    body.mass = 2.0;
    body.inertia = solid_sphere_inertia(2.0, 0.1);
    const BodyId moving = world.create_body(body);
    BallJointDef j;
    j.body_a = anchor;
    j.body_b = moving;
    j.spring = Spring::soft(hertz, 0.0);
    world.create_ball_joint(j);
    const double k = j.spring.stiffness(body.mass);  // anchored at the centre: m_eff = m
    const auto energy = [&] {
      const BodyState b = world.body(moving);
      return 0.5 * b.mass * b.linear_velocity.squaredNorm() + 0.5 * k * b.position.squaredNorm();
    };
    const double e0 = energy();
    double previous = e0;
    for (int i = 0; i < 10000; ++i) {
      world.step(1.0 / 60.0);
      const double e = energy();
      // Float state: allow rounding of the stored state (1e-6 of the initial energy).
      ASSERT_LE(e, previous + 1e-6 * e0) << "hertz " << hertz << " step " << i;
      previous = e;
    }
    EXPECT_LT(previous, e0);
  }
}

}  // namespace
}  // namespace softstep
