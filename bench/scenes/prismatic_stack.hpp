// Prismatic stacks: columns of bodies, each on a vertical slider to the one below (the first
// to the static ground), held apart by the sliders' springs against gravity and kept within
// their translation limits: a tower of suspensions. The columns stand 1 m apart on a square
// grid. Used by `softstep profile prismatic-stack` and the joint benchmarks.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct PrismaticStackOptions {
  int columns = 100;  // >= 1
  int height = 10;    // bodies per column, >= 1
  double spacing = 0.5;  // m, rest distance between a body and the one below
  // Each slider: translation 0 at the rest spacing; the spring pulls towards it, the limit
  // stops the compression and extension beyond it.
  AxisSpring spring{Spring::soft(4.0, 0.5), 0.0};
  AxisLimit limit{true, -0.2, 0.1};  // m
  LinearMotor motor;                 // off by default
  double mass = 1.0;                 // kg, a cube of side 0.3 m
};

struct PrismaticStackScene {
  std::vector<BodyId> grounds;               // one static body per column
  std::vector<std::vector<BodyId>> columns;  // [column][body], bottom first
  std::vector<JointId> joints;               // column by column, bottom first
};

PrismaticStackScene build_prismatic_stack(World& world, const PrismaticStackOptions& options);

}  // namespace softstep::scenes
