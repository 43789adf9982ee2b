// The suspension bridge crossed (bench/scenes/suspension_bridge.hpp): a 500 kg cart on four
// motored wheel joints drives from the left pier over the planks to the right pier, its
// wheels on the planks through the scene's contacts (a sphere against an oriented box).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "frame_constants.hpp"
#include "scenes/chain_scene.hpp"
#include "scenes/suspension_bridge.hpp"

namespace softstep {
namespace {

using test::kDt;

// The cart's centre goes from 3 m before the left tower to past the right one. At the motors'
// 2 m/s the 21 m between the towers take 10.5 s; the deck's slopes (up to about 30 degrees
// at the towers, steeper beside the load) slow it, so it must be across within twice that,
// 1,260 steps (or it is stuck). The deck stays connected: every joint's error (its position
// rows' C, m) stays under 5 cm over the run, a tenth of a plank, while a cart of ten planks'
// weight rolls over it. Under the cart at mid-span the cables sag within 10 % of the static
// solution with the cart's axles on the stations (the cart moves, and the rods stretch).
TEST(BridgeCrossing, TheCartCrossesFromPierToPierOnAConnectedDeck) {
  scenes::SuspensionBridgeOptions o;
  World world;
  scenes::SuspensionBridgeScene scene = scenes::build_suspension_bridge(world, o);
  const BodyId cart = scene.carts[0].chassis;
  EXPECT_LT(world.body(cart).position.x(), 0.0);
  std::vector<ContactManifold> contacts;
  double worst_joint_error = 0.0;
  const int max_steps = static_cast<int>(2.0 * scene.span / o.cart_speed / kDt);
  int step = 0;
  while (step < max_steps && std::isnan(scene.crossings[0].left_s)) {
    scenes::bridge_contacts(world, scene, contacts);
    world.step(kDt, contacts);
    scenes::track_carts(world, scene, ++step * kDt);
    worst_joint_error = std::max(worst_joint_error, scenes::joint_errors(world, scene.joints).max);
  }
  const scenes::Crossing& c = scene.crossings[0];
  ASSERT_FALSE(std::isnan(c.left_s)) << "the cart is at x = " << world.body(cart).position.x()
                                     << " m after " << step << " steps";
  EXPECT_GT(world.body(cart).position.x(), scene.span);
  EXPECT_GE(c.crossing_s(), scene.span / o.cart_speed);  // never faster than its motors
  EXPECT_LT(worst_joint_error, 0.05);
  EXPECT_NEAR(c.sag_at_mid, scene.loaded_static_sag, 0.1 * scene.loaded_static_sag);
  EXPECT_GT(scene.loaded_static_sag, scene.static_sag);
}

}  // namespace
}  // namespace softstep
