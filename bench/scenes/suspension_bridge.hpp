// A suspension bridge: `stations` planks hung between two towers from two cables. Each cable
// is a chain of distance joints (rigid rods of `segment` m) between cable nodes, tied to the
// towers at both ends; each plank hangs below the left and the right node of its station on
// revolute joints about the cross axis z (it swings like a pendulum, level at rest). A heavy
// load hangs from the middle plank on a ball joint: it stands for a body crossing the bridge
// (no contacts exist yet to let one roll across). Used by `softstep profile
// suspension-bridge`.
//
// The static solution (static_sag): every station is a point weight W_j on the cables (its
// plank, its two nodes, and the load at the middle), so each cable is a chain of massless
// rods with lumped weights, a discrete catenary: the horizontal tension H is the same in
// every rod, the vertical one drops by W_j at station j, starting from half the total
// weight (the loads are symmetric), and rod k points along (H, -V_k). H follows from the
// towers' distance (sum of the rods' horizontal lengths), found by bisection; the sag is the
// depth of the lowest node below the towers' anchors.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct SuspensionBridgeOptions {
  int bridges = 1;         // side by side, 10 m apart along z
  int stations = 21;       // planks, odd (one in the middle carries the load), >= 1
  double segment = 1.0;    // m, cable rod length
  double slack_ratio = 0.9;  // towers' distance / the cable's length
  double plank_mass = 50.0;  // kg, 0.9 x 0.1 x 3 m
  double node_mass = 40.0;   // kg per cable node (heavy enough that the rods barely stretch)
  double load_mass = 500.0;  // kg
  double width = 3.0;        // m, between the cables
  double damping = 0.5;      // 1/s linear damping of every body, so the bridge settles
};

struct SuspensionBridgeScene {
  std::vector<BodyId> nodes;  // left cable then right cable, tower to tower
  std::vector<BodyId> planks;
  BodyId load;
  std::vector<JointId> joints;
  double tower_height = 0.0;  // m, the cables' anchors
  double static_sag = 0.0;    // m, derived (see above)
};

SuspensionBridgeScene build_suspension_bridge(World& world, const SuspensionBridgeOptions& options);

// The depth of bridge 0's lowest left cable node below the towers' anchors now, m.
double measured_sag(const World& world, const SuspensionBridgeScene& scene,
                    const SuspensionBridgeOptions& options);

}  // namespace softstep::scenes
