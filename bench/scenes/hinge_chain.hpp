// Hinge chains: N box links on revolute joints about z (each swings in the chain's vertical
// plane), M parallel chains, the first link hinged to the static world, laid out along +x so
// they swing down under gravity. Optional angle limits, motors (speed 0 with a max torque is
// joint friction) and torsion springs on every hinge. With `weld` the links are welded
// instead (a cantilever chain that droops under gravity when its angular half is soft).
// Used by `softstep profile hinge-chain` and the joint benchmarks.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct HingeChainOptions {
  int links = 1000;  // per chain, >= 1
  int chains = 1;    // >= 1, 1 m apart along z
  AxisLimit limit;   // rad, on every hinge
  AngularMotor motor;
  AxisSpring spring;  // torsion spring towards `target` (0: straight)
  bool weld = false;  // weld the links instead (limit, motor and spring unused)
  Spring weld_linear = Spring::rigid();
  Spring weld_angular = Spring::soft(5.0, 0.7);
  double link_mass = 1.0;      // kg, box 0.25 x 0.05 x 0.05 m
  double link_spacing = 0.25;  // m, centre to centre
};

struct HingeChainScene {
  std::vector<BodyId> anchors;             // one static body per chain
  std::vector<std::vector<BodyId>> links;  // [chain][link]
  std::vector<JointId> joints;             // chain by chain, from the anchor out
};

HingeChainScene build_hinge_chain(World& world, const HingeChainOptions& options);

}  // namespace softstep::scenes
