// The exact sub-step reference (reference.hpp) against closed forms (analytic.hpp), and the
// solver's iterations against the reference.
#include "softstep/reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "frame_constants.hpp"
#include "scenes/chain_scene.hpp"
#include "softstep/analytic.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

// One sub-step, no relax pass and no geometric-stiffness inertia: the velocities a step ends
// with are the ones its solve produced.
WorldSettings single_solve_settings() {
  WorldSettings s;
  s.substeps = 1;
  s.relax_iterations = 0;
  s.geometric_stiffness = false;
  return s;
}

using test::kDt;

// A body on a soft ball joint anchored at its centre of mass sees m_eff = m on every axis:
// the exact solve must be the talk's implicit-Euler spring (2:3:1).
TEST(ExactReference, MatchesTheTalksSoftConstraint) {
  WorldSettings settings = single_solve_settings();
  settings.gravity.setZero();
  World world(settings);
  world.set_solve_capture(true);
  BodyDef ground;
  ground.type = BodyType::Static;
  const double mass = 2.0, x0 = 0.5, v1 = 1.5, hertz = 5.0, zeta = 0.3;
  BodyDef body;
  body.position = {x0, 0.0, 0.0};
  body.linear_velocity = {v1, 0.0, 0.0};
  body.mass = mass;
  body.inertia = solid_sphere_inertia(mass, 0.1);
  BallJointDef joint;
  joint.body_a = world.create_body(ground);
  joint.body_b = world.create_body(body);
  joint.spring = Spring::soft(hertz, zeta);
  world.create_ball_joint(joint);
  world.step(kDt);

  const reference::SoftSystem system = reference::first_substep_system(world);
  const reference::ExactSolution exact = reference::solve_exact(system);
  const double omega = 2.0 * std::numbers::pi * hertz;
  const double expected = analytic::implicit_euler_spring_velocity(
      x0, v1, mass, mass * omega * omega, 2.0 * mass * zeta * omega, system.h);
  ASSERT_EQ(system.body_slots.size(), 2u);
  const int moving = system.body_slots[0] == joint.body_b.index ? 0 : 6;
  EXPECT_NEAR(exact.velocity[moving], expected, 1e-6 * std::abs(expected));
  EXPECT_NEAR(exact.velocity.segment<2>(moving + 1).norm(), 0.0, 1e-12);
  EXPECT_LT(reference::row_residual(system, exact.velocity, exact.impulse).norm(), 1e-12);
  // One soft row, solved once, is exact: the solver agrees to float rounding, and so its
  // rows' residual vanishes.
  EXPECT_LT(reference::row_residual(system, system.velocity_after_solve, system.impulse_after_solve)
                .norm(),
            1e-5 * std::abs(v1));
  EXPECT_NEAR(world.body(joint.body_b).linear_velocity.x(), expected, 1e-5 * std::abs(expected));
}

// A pendulum on a rigid rod, the rod 1 mm too long and the bob moving: along the rod the row
// is the rigid rows' stiff spring (min(rigid_hertz, substep rate / 4), zeta 2) as implicit
// Euler; across the rod nothing changes.
TEST(ExactReference, MatchesTheSinglePendulumRow) {
  const WorldSettings settings = single_solve_settings();
  World world(settings);
  world.set_solve_capture(true);
  BodyDef pivot;
  pivot.type = BodyType::Static;
  const double mass = 3.0, length = 1.2, angle = 0.4, stretch = 1e-3;
  const Eigen::Vector3d n(std::sin(angle), -std::cos(angle), 0.0);  // pivot to bob
  const Eigen::Vector3d t(std::cos(angle), std::sin(angle), 0.0);   // across the rod
  BodyDef bob;
  bob.position = (length + stretch) * n;
  bob.linear_velocity = 0.7 * t + 0.2 * n;
  bob.mass = mass;
  bob.inertia = solid_sphere_inertia(mass, 0.1);
  DistanceJointDef rod;
  rod.body_a = world.create_body(pivot);
  rod.body_b = world.create_body(bob);
  rod.rest_length = length;
  world.create_distance_joint(rod);
  world.step(kDt);

  const reference::SoftSystem system = reference::first_substep_system(world);
  const reference::ExactSolution exact = reference::solve_exact(system);
  const int moving = system.body_slots[0] == rod.body_b.index ? 0 : 6;
  const Eigen::Vector3d v0 = system.velocity_before.segment<3>(moving);
  const Eigen::Vector3d v = exact.velocity.segment<3>(moving);
  const double omega = 2.0 * std::numbers::pi * std::min(settings.rigid_hertz, 0.25 / system.h);
  const double along = analytic::implicit_euler_spring_velocity(
      stretch, v0.dot(n), mass, mass * omega * omega,
      2.0 * mass * settings.rigid_damping_ratio * omega, system.h);
  EXPECT_NEAR(v.dot(n), along, 1e-6 * std::abs(along));
  EXPECT_NEAR(v.dot(t), v0.dot(t), 1e-9);
  EXPECT_NEAR(v.z(), 0.0, 1e-12);
}

// A chain laid out at its analytic equilibrium stretch (each joint C = T / (m_eff omega^2),
// hanging_chain_test.cpp) is held at rest by impulses h T: the exact solve must find both.
TEST(ExactReference, HoldsAHangingChainWithTheAnalyticTension) {
  const WorldSettings settings = single_solve_settings();
  const double h = static_cast<float>(kDt);  // the solver's sub-step is a float
  const double omega = 2.0 * std::numbers::pi * std::min(settings.rigid_hertz, 0.25 / h);
  scenes::ChainOptions o;
  o.layout = scenes::ChainLayout::Hanging;
  o.link_masses = {1.0, 2.0, 1.5, 0.5, 3.0, 1.0};
  const double g = -settings.gravity.y();
  const std::vector<double> tension = analytic::hanging_chain_tension(o.link_masses, g);
  for (std::size_t i = 0; i < tension.size(); ++i) {
    const double inverse_mass_a = i == 0 ? 0.0 : 1.0 / o.link_masses[i - 1];
    const double effective_mass = 1.0 / (inverse_mass_a + 1.0 / o.link_masses[i]);
    o.joint_gaps.push_back(tension[i] / (effective_mass * omega * omega));
  }
  World world(settings);
  world.set_solve_capture(true);
  const scenes::ChainScene scene = scenes::build_chain(world, o);
  world.step(kDt);

  const reference::SoftSystem system = reference::first_substep_system(world);
  const reference::ExactSolution exact = reference::solve_exact(system);
  ASSERT_EQ(exact.impulse.size(), 3 * static_cast<long>(tension.size()));
  for (std::size_t i = 0; i < tension.size(); ++i) {
    EXPECT_NEAR(exact.impulse[3 * static_cast<long>(i) + 1] / h, tension[i], 1e-6 * tension[i])
        << "joint " << i;
  }
  EXPECT_LT(exact.velocity.lpNorm<Eigen::Infinity>(), 1e-6 * g * h);
  EXPECT_EQ(exact.bounded_rows, 0);
  (void)scene;
}

// The distance of the solver's velocities from the exact solution after `iterations` solve
// passes, on a 100-link rigid chain caught mid-swing.
double distance_after(int iterations) {
  World world(single_solve_settings());
  scenes::ChainOptions o;
  o.links = 100;
  scenes::build_chain(world, o);
  for (int i = 0; i < 20; ++i) world.step(kDt);
  WorldSettings s = world.settings();
  s.solve_iterations = iterations;
  world.set_settings(s);
  world.set_solve_capture(true);
  world.step(kDt);
  const reference::SoftSystem system = reference::first_substep_system(world);
  const reference::ExactSolution exact = reference::solve_exact(system);
  EXPECT_EQ(exact.bounded_rows, 0);
  return reference::reference_distance(system, exact);
}

TEST(ExactReference, IterationsConvergeToItOnAHundredLinkChain) {
  double previous = std::numeric_limits<double>::infinity();
  for (int iterations : {1, 2, 4, 8, 16, 32, 64}) {
    const double d = distance_after(iterations);
    EXPECT_LT(d, previous) << iterations << " iterations";
    previous = d;
  }
  // Measured: 0.34 after one pass, 1.7e-4 after 32, 2.9e-6 after 64 (float rounding from
  // there on). Converged means within the 1e-4.
  EXPECT_LT(distance_after(256), 1e-4);
}

// The closed forms agree with each other: the talk's implicit-Euler spring converges to the
// exact oscillator as h -> 0, at first order, for any damping.
TEST(Analytic, ImplicitEulerSpringConvergesToTheExactOscillator) {
  const double mass = 2.0, omega = 2.0 * std::numbers::pi * 3.0, x0 = 0.1, v0 = -0.5, t = 0.4;
  for (const double zeta : {0.0, 0.3, 1.0, 2.5}) {
    const double exact = analytic::harmonic_oscillator_position(x0, v0, omega, zeta, t);
    const auto error_at = [&](int steps) {
      const double h = t / steps;
      double x = x0, v = v0;
      for (int i = 0; i < steps; ++i) {
        v = analytic::implicit_euler_spring_velocity(x, v, mass, mass * omega * omega,
                                                     2.0 * mass * zeta * omega, h);
        x += h * v;
      }
      return std::abs(x - exact);
    };
    const double coarse = error_at(4000), fine = error_at(8000);
    EXPECT_LT(fine, 1e-3 * x0) << "zeta " << zeta;
    EXPECT_NEAR(coarse / fine, 2.0, 0.1) << "zeta " << zeta;  // first order
  }
  // Small-angle pendulum: a point mass on a rod of length L swings at sqrt(g / L).
  EXPECT_DOUBLE_EQ(analytic::small_angle_pendulum_frequency(2.0, 0.5, 0.0, 9.81),
                   std::sqrt(9.81 / 0.5));
  EXPECT_DOUBLE_EQ(analytic::small_angle_pendulum_angle(0.1, 2.0, std::numbers::pi), 0.1);
}

// Capturing only copies: the step, with one thread or two, is bit for bit the same.
TEST(SolveCapture, LeavesTheStepUnchanged) {
  std::vector<std::uint64_t> hashes;
  for (const bool capture : {false, true}) {
    for (const int threads : {1, 2}) {
      WorldSettings s;
      s.threads = threads;
      World world(s);
      scenes::ChainOptions o;
      o.links = 2100;  // enough work for the step to use both threads
      scenes::build_chain(world, o);
      world.set_solve_capture(capture);
      for (int i = 0; i < 3; ++i) world.step(kDt);
      hashes.push_back(world.state_hash());
    }
  }
  for (std::uint64_t h : hashes) EXPECT_EQ(h, hashes.front());
}

}  // namespace
}  // namespace softstep
