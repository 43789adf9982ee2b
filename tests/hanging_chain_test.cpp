// A rigid 100-link chain hanging under gravity settles, and its joints stretch no more than
// Soft Step's rigid rows allow.
//
// The bound, derived: a rigid row is solved as a stiff spring of angular frequency
// omega = 2 pi min(rigid_hertz, substep_rate / 4), and relaxed without bias. At rest the
// solve leaves no velocity, so bias_rate C + (gamma/h) P = 0 with P = T h (T the tension):
// C = T / k with k = m_eff omega^2 (talk 2:3:2). Joint i (from the top, 0-based) carries the
// weight of the N - i links below it; along the chain the anchor offsets are parallel to the
// axis, so rotation adds nothing and m_eff = m for the top joint (the other side is static)
// and m/2 below. The largest stretch is therefore at joint 1:
//   C_max = 2 (N - 1) g / omega^2.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

TEST(HangingChain, RigidChainStretchStaysWithinTheDerivedBound) {
  WorldSettings s;  // defaults: 4 sub-steps, 1 relax, rigid 60 Hz
  // The slow bungee modes settle below the sleep speed long before the top force converges.
  s.sleeping = false;
  World world(s);
  scenes::ChainOptions o;
  o.links = 100;
  o.layout = scenes::ChainLayout::Hanging;
  const scenes::ChainScene scene = scenes::build_chain(world, o);
  const double dt = 1.0 / 60.0;
  // Laid out unstretched, the chain must stretch ~0.7 m in all and bounces like a bungee
  // before it settles: its long modes are lightly damped. 80 s is settled to < 1 mm/s.
  for (int i = 0; i < 80 * 60; ++i) world.step(dt);

  const double substep_rate = s.substeps / dt;
  const double omega = 2.0 * std::numbers::pi * std::min(s.rigid_hertz, 0.25 * substep_rate);
  const double bound = 2.0 * (o.links - 1) * 9.81 / (omega * omega);
  const scenes::JointErrors e = scenes::joint_errors(world, scene.joints);
  EXPECT_LT(e.max, 1.05 * bound);
  // The bound is tight, not just true: the steady state reaches it.
  EXPECT_GT(e.max, 0.9 * bound);
  // Settled: no link moves faster than 1 mm/s.
  for (BodyId b : scene.links[0]) EXPECT_LT(world.body(b).linear_velocity.norm(), 1e-3);
  // The top joint carries the whole chain's weight.
  const double top_force = world.joint_reading(scene.joints.front()).force.y();
  EXPECT_NEAR(top_force, o.links * o.link_mass * 9.81, 1e-3 * o.links * 9.81);
}

}  // namespace
}  // namespace softstep
