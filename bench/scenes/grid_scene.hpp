// The joint-grid scene (a net or cloth-like lattice): N x N solid spheres 1 m apart in a
// vertical plane, the top row static, each body ball-jointed to its right and lower
// neighbours at the midpoint. The field's classic joint benchmark: at N = 100, 10,000 bodies
// and 19,800 joints.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct GridOptions {
  int size = 100;           // N, >= 2
  double radius = 0.4;      // m
  double density = 1000.0;  // kg/m^3
  double spacing = 1.0;     // m, centre to centre
  Spring spring = Spring::rigid();
};

struct GridScene {
  std::vector<BodyId> bodies;  // row-major, row 0 at the top (static)
  std::vector<JointId> joints;
};

GridScene build_grid(World& world, const GridOptions& options);

}  // namespace softstep::scenes
