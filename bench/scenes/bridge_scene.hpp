// A bridge: a chain of `span` links pinned to the static world at both ends, loaded by heavy
// bodies hanging from evenly spaced links on rigid rods. Links as in the chain scene (1 kg
// spheres of radius 0.1 m, 0.25 m apart, ball joints at the midpoints), hanging slack between
// piers 10 % closer than its length, laid out along a parabola of its exact length.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct BridgeOptions {
  int span = 1000;                  // links between the two anchors, >= 2
  int loads = 10;                   // heavy bodies, >= 0, at most span
  double load_mass = 50.0;          // kg
  double load_radius = 0.3;         // m
  double rod_length = 0.5;          // m, from the link's centre to the load's centre
  double slack_ratio = 0.9;  // piers' distance / the deck's length: the deck hangs slack
  Spring spring = Spring::rigid();  // of the span's joints
};

struct BridgeScene {
  std::vector<BodyId> links;
  std::vector<BodyId> loads;
  std::vector<JointId> joints;  // span joints first, then the rods
};

BridgeScene build_bridge(World& world, const BridgeOptions& options);

}  // namespace softstep::scenes
