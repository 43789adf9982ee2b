// The talk's central claim (slides 2:3:1-2:3:2): a soft constraint stepped with
// semi-implicit Euler is exactly the implicit-Euler spring-damper. A body on a soft ball
// joint to the static world, anchored at its centre of mass so it sees m_eff = m, must
// follow the implicit-Euler recurrence to float rounding, even at k = 1e9 where explicit
// integration explodes.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

struct Case {
  double k, c, h, mass;
};

void PrintTo(const Case& p, std::ostream* os) {
  *os << "k " << p.k << " c " << p.c << " h " << p.h << " m " << p.mass;
}

class TalkIdentity : public ::testing::TestWithParam<Case> {};

// v2 = (v1 - h k/m x1) / (1 + h c/m + h^2 k/m),  x2 = x1 + h v2   (talk 2:3:1, implicit Euler)
void implicit_euler(double& x, double& v, const Case& p) {
  v = (v - p.h * p.k / p.mass * x) / (1.0 + p.h * p.c / p.mass + p.h * p.h * p.k / p.mass);
  x = x + p.h * v;
}

TEST_P(TalkIdentity, SoftConstraintEqualsImplicitEulerSpring) {
  const Case p = GetParam();
  WorldSettings settings;
  settings.gravity.setZero();
  settings.substeps = 1;
  settings.relax_iterations = 1;  // springs are not relaxed: the identity must hold anyway
  // The identity is followed down to micrometres, where a slow spring would fall asleep.
  settings.sleeping = false;
  World world(settings);
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId anchor = world.create_body(ground);
  const double x0 = 0.5;
  BodyDef body;
  body.position = {x0, 0.0, 0.0};
  body.mass = p.mass;
  body.inertia = solid_sphere_inertia(p.mass, 0.1);
  const BodyId moving = world.create_body(body);
  BallJointDef joint;
  joint.body_a = anchor;
  joint.body_b = moving;
  joint.spring = Spring::from_stiffness(p.k, p.c, p.mass);
  world.create_ball_joint(joint);

  double x = x0, v = 0.0, worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    world.step(p.h);
    implicit_euler(x, v, p);
    const BodyState s = world.body(moving);
    worst = std::max(worst, std::abs(s.position.x() - x));
    ASSERT_NEAR(s.position.y(), 0.0, 1e-12);
  }
  // Float rounding: the solver works in float (~6e-8 relative), per step, on an amplitude
  // of x0, and implicit Euler is contractive, so errors do not pile up.
  EXPECT_LT(worst, 2e-6 * x0) << "k " << p.k << " c " << p.c << " h " << p.h;
}

INSTANTIATE_TEST_SUITE_P(
    SeveralSprings, TalkIdentity,
    ::testing::Values(Case{100.0, 0.0, 1.0 / 60.0, 1.0}, Case{100.0, 2.0, 1.0 / 60.0, 1.0},
                      Case{1.0e4, 50.0, 1.0 / 60.0, 2.5}, Case{1.0e6, 0.0, 1.0 / 30.0, 1.0},
                      Case{1.0e9, 0.0, 1.0 / 60.0, 1.0}, Case{1.0e9, 1.0e3, 1.0 / 30.0, 3.0}));

// The k = 1e9 case is a real test: explicit Euler (talk 1:2:1) sends it to Neptune.
TEST(TalkIdentity, ExplicitEulerExplodesAtTheStiffestCase) {
  const double k = 1.0e9, m = 1.0, h = 1.0 / 60.0;
  double x = 0.5, v = 0.0;
  for (int i = 0; i < 20; ++i) {
    const double x_next = x + h * v;
    v = v - h * k / m * x;
    x = x_next;
  }
  EXPECT_GT(std::abs(x), 1e20);
}

}  // namespace
}  // namespace softstep
