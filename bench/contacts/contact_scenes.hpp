// Contact scenes for the benchmarks, each with its Bullet narrow phase.
//   pyramid  a single-layer wall of 1 m, 100 kg boxes in one vertical plane, base N, each row
//            offset by half a box, on a static ground (base 100: 5,050 boxes)
//   pile     boxes and spheres dropped into an open box
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contacts/bullet_contacts.hpp"

namespace softstep::bench {

struct ContactScene {
  std::unique_ptr<World> world;
  std::unique_ptr<BulletContacts> collision;
  std::vector<BodyId> dynamic;  // the moving bodies, in creation order
  double friction = 0.6;
  double restitution = 0.0;
};

ContactScene make_pyramid(int base, const WorldSettings& settings);
ContactScene make_pile(int count, const WorldSettings& settings);

}  // namespace softstep::bench
