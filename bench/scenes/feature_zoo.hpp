#pragma once

#include "softstep/softstep.hpp"

namespace softstep::scenes {

// Every ball and distance joint kind the kernels have a variant for, in one world: rigid,
// soft and free ball joints; distance rods, springs with min, max and both limits, ropes
// (free + max), a free spring with a min limit. Twelve-link chains from a static ceiling, so
// that joints share bodies and colours. Its trajectory is frozen in golden_hash_test.cpp:
// change it and those hashes no longer prove anything.
void build_feature_zoo(World& world, double damping);

}  // namespace softstep::scenes
