// A suspension bridge crossed by a cart: `stations` nodes on each of two cables, each cable a
// chain of distance joints (rigid rods of `segment` m) tied to the towers at both ends, and a
// deck of planks between them: plank k spans from station k to station k + 1 (the towers
// are stations 0 and stations + 1), its top face's near edge on revolute joints about the
// cross axis z at both cables' nodes, its far edge on ball joints at the next nodes, so the
// deck follows the cables without steps. Piers at both towers carry the deck's ends. A cart
// (vehicle_scene.hpp's car: a chassis on four sprung, motored wheel joints) starts at rest on
// the left pier, drives across on its wheel motors and brakes once on the right pier. Its
// wheels touch the planks and piers through contacts the scene computes each step
// (bridge_contacts: a wheel is a sphere, a plank an oriented box, sphere_contacts.hpp); the
// cart's chassis has no contacts. Used by `softstep profile suspension-bridge`.
//
// The static solution (static_sag, loaded_static_sag): every station is a point weight W_j on
// each cable (its node and half of each plank it carries: plank / 2 in all, split between
// the cables), so each cable is a chain of massless rods with lumped weights, a discrete
// catenary: the horizontal tension H is the same in every rod, the vertical one drops by W_j
// at station j, and rod k points along (H, -V_k). H follows from the towers' distance (sum of
// the rods' horizontal lengths), found by bisection; the sag is the depth of the lowest node
// below the towers' anchors. Under the cart at mid-span, each of its axles (half the cart's
// weight, a quarter on each cable) is split between the two stations of the plank under it by
// the lever rule, at the loaded shape's own positions (a fixed point, iterated).
#pragma once

#include <limits>
#include <vector>

#include "scenes/vehicle_scene.hpp"
#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct SuspensionBridgeOptions {
  int bridges = 1;         // side by side, 10 m apart along z
  int stations = 21;       // cable nodes per cable, >= 1
  double segment = 1.0;    // m, cable rod length (and plank length)
  double slack_ratio = 0.95;  // towers' distance / the cable's length
  double plank_mass = 50.0;   // kg, segment x 0.1 x width
  double node_mass = 40.0;    // kg per cable node (heavy enough that the rods barely stretch)
  double load_mass = 500.0;   // kg, the cart: its chassis and four 20 kg wheels
  double cart_speed = 2.0;    // m/s, its wheel motors' target
  double cart_motor_torque = 300.0;  // N m per wheel
  double width = 3.0;        // m, between the cables
  double damping = 0.5;      // 1/s linear damping of every bridge body, so the bridge settles
};

// A cart's way across, seconds since the start (NaN until it happens).
struct Crossing {
  static constexpr double kNotYet = std::numeric_limits<double>::quiet_NaN();
  double entered_s = kNotYet;  // its centre passed the left tower
  double left_s = kNotYet;     // its centre passed the right tower
  double sag_at_mid = kNotYet;  // m, the bridge's sag when its centre passed mid-span
  bool braked = false;          // its motors stopped it on the right pier
  double crossing_s() const { return left_s - entered_s; }
};

struct SuspensionBridgeScene {
  std::vector<BodyId> nodes;  // per bridge: left cable then right cable, tower to tower
  std::vector<BodyId> planks;
  std::vector<BodyId> piers;  // static, two per bridge
  std::vector<Car> carts;     // one per bridge
  std::vector<JointId> joints;
  std::vector<Crossing> crossings;  // one per cart
  VehicleOptions cart;              // how the carts were built
  double span = 0.0;                // m, tower to tower along x
  double tower_height = 0.0;        // m, the cables' anchors and the piers' tops
  double static_sag = 0.0;          // m, unloaded (see above)
  double loaded_static_sag = 0.0;   // m, the cart at mid-span (see above)
  Eigen::Vector3d plank_half = Eigen::Vector3d::Zero();
  Eigen::Vector3d pier_half = Eigen::Vector3d::Zero();
};

SuspensionBridgeScene build_suspension_bridge(World& world, const SuspensionBridgeOptions& options);

// The carts' wheels against the planks and piers for the world's poses now, into `out`
// (cleared first), in a fixed order: bridge by bridge, wheel by wheel, plank by plank.
void bridge_contacts(const World& world, const SuspensionBridgeScene& scene,
                     std::vector<ContactManifold>& out);

// After a step that ended at `time` s: notes where each cart is (scene.crossings) and brakes
// the carts that reached the right pier.
void track_carts(World& world, SuspensionBridgeScene& scene, double time);

// The depth of a bridge's lowest left cable node below the towers' anchors now, m.
double measured_sag(const World& world, const SuspensionBridgeScene& scene,
                    const SuspensionBridgeOptions& options, int bridge = 0);

}  // namespace softstep::scenes
