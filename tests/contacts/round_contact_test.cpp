// Round shapes in contacts (ContactManifold::radius_a / radius_b): a sphere rolling fast on a
// plane keeps its centre at the height of the resting sphere when its contact is given as its
// centre and radius, and sinks by the rise of its turning surface point when the contact is
// given as that point (the way every contact was solved before radii).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contacts/analytic_contacts.hpp"

namespace softstep::test {
namespace {

constexpr double kBallRadius = 0.3;  // m
constexpr double kSpin = 30.0;       // rad/s: rolls at 9 m/s, turning 0.5 rad per step

// The lowest height the ball's centre reaches from 1 s to 3 s of rolling (after the drop
// from its release just touching has settled).
double lowest_centre(bool round) {
  WorldSettings s;
  s.sleeping = false;
  s.substeps = 4;
  World world(s);
  const BodyId ground = add_ground(world);
  BodyDef d;
  d.position = {0.0, kBallRadius, 0.0};
  d.mass = 10.0;
  d.inertia = solid_sphere_inertia(d.mass, kBallRadius);
  d.linear_velocity = {kSpin * kBallRadius, 0.0, 0.0};
  d.angular_velocity = {0.0, 0.0, -kSpin};  // rolling along +x without slip
  const BodyId ball = world.create_body(d);
  double lowest = kBallRadius;
  for (int i = 0; i < 180; ++i) {
    ContactManifold m = round ? round_sphere_on_ground(world, ground, ball, kBallRadius)
                              : sphere_on_ground(world, ground, ball, kBallRadius);
    m.friction = 0.6;
    world.step(kDt, {&m, 1});
    if (i >= 60) lowest = std::min(lowest, world.body(ball).position.y());
  }
  // Still rolling without slip at its start speed: friction had nothing to do.
  EXPECT_NEAR(world.body(ball).linear_velocity.x(), kSpin * kBallRadius, 1e-3);
  return lowest;
}

// At rest the contact row (the point straight below the centre: r x n = 0, effective mass m)
// carries m g with the soft step's static impulse, so the contact spring is pressed in by
// g / omega_c^2 (0.276 mm at 30 Hz; contact_physics_test derives it for the box). Given round,
// the rolling ball's core is its centre: turning the body does not move it, so the separation
// the solver follows is the resting ball's and the centre stays at r - g / omega_c^2. The
// bound: 1e-5 m (4 % of the compression) is float rounding of the 4e-4 m sub-step travel
// along the normal and of the rows' impulses with room to spare; an error of the order of the
// old way's sink (below) is 1,000 times larger.
TEST(RoundContacts, ARollingSphereGivenRoundRidesAtTheRestingHeight) {
  const double omega_c = 2.0 * std::numbers::pi * WorldSettings{}.contact.hertz;
  const double compression = 9.81 / (omega_c * omega_c);
  EXPECT_NEAR(lowest_centre(true), kBallRadius - compression, 1e-5);
}

// Given as its lowest point, the anchor turns with the ball: by k sub-steps of h into a step
// it is r (1 - cos(omega k h)) above the ground (3.7 cm after the whole step's 0.5 rad), which
// the solver reads as a gap it lets the ball fall into. The ball sinks by a sizeable part of
// that rise, never by more than the whole step's rise plus the contact spring's compression.
TEST(RoundContacts, ARollingSphereGivenByItsSurfacePointSinksByTheAnchorsRise) {
  const double rise = kBallRadius * (1.0 - std::cos(kSpin * kDt));
  const double sink = kBallRadius - lowest_centre(false);
  EXPECT_GT(sink, 0.25 * rise);
  EXPECT_LT(sink, rise + 1e-3);
}

// The README's round-ball example (cut out of README.md by tests/CMakeLists.txt) as the contact
// of a resting ball: it settles at r - g / omega_c^2 as the derivation above says.
TEST(RoundContacts, TheReadmeExampleRestsABallOnItsContactSpring) {
  World world;
  const BodyId ground = add_ground(world);
  const double r = 0.3;
  BodyDef d;
  d.position = {1.0, r, -2.0};
  d.mass = 10.0;
  d.inertia = solid_sphere_inertia(d.mass, r);
  const BodyId ball = world.create_body(d);
  for (int i = 0; i < 120; ++i) {
    const Eigen::Vector3d centre = world.body(ball).position;
    const double x = centre.x(), z = centre.z(), centre_height = centre.y();
#include "frame_constants.hpp"
#include "readme_examples/round_example.inc"
    world.step(kDt, {&m, 1});
  }
  const double omega_c = 2.0 * std::numbers::pi * world.settings().contact.hertz;
  EXPECT_NEAR(world.body(ball).position.y(), r - 9.81 / (omega_c * omega_c), 1e-5);
}

}  // namespace
}  // namespace softstep::test
