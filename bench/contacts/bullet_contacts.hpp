// The narrow phase of the contact benchmarks: Bullet's collision module (libbullet-dev, its
// btCollisionWorld with the dynamic AABB tree broad phase) finds the manifolds, this turns
// them into softstep::ContactManifold. Bench-only: the library itself takes contacts from any
// collision detection.
#pragma once

#include <memory>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::bench {

class BulletContacts {
 public:
  BulletContacts();
  ~BulletContacts();
  BulletContacts(const BulletContacts&) = delete;
  BulletContacts& operator=(const BulletContacts&) = delete;

  void add_box(BodyId body, const Eigen::Vector3d& half_extents);
  void add_sphere(BodyId body, double radius);
  // Moves every shape to its body's pose and returns this step's manifolds, in Bullet's
  // manifold order (deterministic for a deterministic sequence of poses).
  const std::vector<ContactManifold>& find(const World& world, double friction,
                                           double restitution);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace softstep::bench
