#include "contacts/contact_scenes.hpp"

namespace softstep::bench {
namespace {

BodyId add_static_box(ContactScene& s, const Eigen::Vector3d& position,
                      const Eigen::Vector3d& half) {
  BodyDef d;
  d.type = BodyType::Static;
  d.position = position;
  const BodyId id = s.world->create_body(d);
  s.collision->add_box(id, half);
  return id;
}

BodyId add_dynamic_box(ContactScene& s, const Eigen::Vector3d& position, double mass,
                       const Eigen::Vector3d& half) {
  BodyDef d;
  d.position = position;
  d.mass = mass;
  d.inertia = solid_box_inertia(mass, 2.0 * half);
  const BodyId id = s.world->create_body(d);
  s.collision->add_box(id, half);
  s.dynamic.push_back(id);
  return id;
}

ContactScene empty_scene(const WorldSettings& settings) {
  ContactScene s;
  s.world = std::make_unique<World>(settings);
  s.collision = std::make_unique<BulletContacts>();
  return s;
}

}  // namespace

ContactScene make_pyramid(int base, const WorldSettings& settings) {
  ContactScene s = empty_scene(settings);
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  add_static_box(s, {0.0, -1.0, 0.0}, {double(base) + 10.0, 1.0, 10.0});
  for (int row = 0; row < base; ++row) {
    const int count = base - row;
    for (int i = 0; i < count; ++i) {
      const double x = (double(i) - 0.5 * double(count - 1)) * 1.0;
      add_dynamic_box(s, {x, 0.5 + double(row), 0.0}, 100.0, half);
    }
  }
  return s;
}

ContactScene make_pile(int count, const WorldSettings& settings) {
  ContactScene s = empty_scene(settings);
  const double size = 6.0;
  add_static_box(s, {0.0, -0.5, 0.0}, {size + 1.0, 0.5, size + 1.0});
  for (int side = 0; side < 4; ++side) {
    const double sx = side < 2 ? (side == 0 ? -size : size) : 0.0;
    const double sz = side >= 2 ? (side == 2 ? -size : size) : 0.0;
    const Eigen::Vector3d half =
        side < 2 ? Eigen::Vector3d(0.25, 2.0, size) : Eigen::Vector3d(size, 2.0, 0.25);
    add_static_box(s, {sx, 2.0, sz}, half);
  }
  // A lattice of alternating boxes and spheres above the bin, a little jittered by index.
  const int per_side = 8;
  for (int i = 0; i < count; ++i) {
    const int layer = i / (per_side * per_side);
    const int in_layer = i % (per_side * per_side);
    const Eigen::Vector3d p(-5.0 + 1.3 * double(in_layer % per_side) + 0.1 * double(layer % 3),
                            2.0 + 1.3 * double(layer),
                            -5.0 + 1.3 * double(in_layer / per_side) + 0.07 * double(i % 5));
    if (i % 2 == 0) {
      add_dynamic_box(s, p, 1.0, {0.4, 0.4, 0.4});
    } else {
      BodyDef d;
      d.position = p;
      d.mass = 1.0;
      d.inertia = solid_sphere_inertia(1.0, 0.45);
      const BodyId id = s.world->create_body(d);
      s.collision->add_sphere(id, 0.45);
      s.dynamic.push_back(id);
    }
  }
  return s;
}

}  // namespace softstep::bench
