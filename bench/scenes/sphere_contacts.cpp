#include "scenes/sphere_contacts.hpp"

#include <cmath>

namespace softstep::scenes {

namespace {

// One point: `on_a` the closest point of A (world), n the unit normal from A to B.
ContactManifold one_point(const BodyState& a, BodyId a_id, const SphereShape& sphere, const Eigen::Vector3d& on_a,
                          const Eigen::Vector3d& n, double separation, double friction) {
  ContactManifold m;
  m.body_a = a_id;
  m.body_b = sphere.body;
  m.normal = n;
  m.friction = friction;
  m.point_count = 1;
  m.points[0].anchor_a = a.orientation.inverse() * (on_a - a.position);
  // The sphere is round: its anchor is its centre (its centre of mass) and radius_b puts the
  // surface below it, so the point does not turn up off the ground as the wheel rolls.
  m.points[0].anchor_b = Eigen::Vector3d::Zero();
  m.radius_b = sphere.radius;
  m.points[0].separation = separation;
  m.points[0].feature_id = 0;
  return m;
}

}  // namespace

std::optional<ContactManifold> sphere_on_plane(const World& world, BodyId ground, double height,
                                               const SphereShape& sphere, double margin,
                                               double friction) {
  const BodyState b = world.body(sphere.body);
  const double separation = b.position.y() - height - sphere.radius;
  if (separation > margin) return std::nullopt;
  return one_point(world.body(ground), ground, sphere,
                   {b.position.x(), height, b.position.z()}, Eigen::Vector3d::UnitY(), separation,
                   friction);
}

std::optional<ContactManifold> sphere_on_box(const World& world, BodyId box,
                                             const Eigen::Vector3d& half,
                                             const SphereShape& sphere, double margin,
                                             double friction) {
  const BodyState a = world.body(box);
  const BodyState b = world.body(sphere.body);
  const Eigen::Vector3d centre = a.orientation.inverse() * (b.position - a.position);
  // A cheap rejection first: most wheel-plank pairs are far apart.
  if ((centre.cwiseAbs() - half).maxCoeff() > sphere.radius + margin) return std::nullopt;
  const Eigen::Vector3d closest = centre.cwiseMax(-half).cwiseMin(half);
  Eigen::Vector3d normal;
  double separation;
  Eigen::Vector3d on_box = closest;
  if (closest == centre) {
    // The centre is inside: leave through the nearest face.
    const Eigen::Vector3d depth = half - centre.cwiseAbs();
    int axis = 0;
    depth.minCoeff(&axis);
    const double side = centre[axis] < 0.0 ? -1.0 : 1.0;
    normal = Eigen::Vector3d::Zero();
    normal[axis] = side;
    on_box[axis] = side * half[axis];
    separation = -depth[axis] - sphere.radius;
  } else {
    const Eigen::Vector3d gap = centre - closest;
    const double distance = gap.norm();
    normal = gap / distance;
    separation = distance - sphere.radius;
  }
  if (separation > margin) return std::nullopt;
  return one_point(a, box, sphere, a.position + a.orientation * on_box,
                   a.orientation * normal, separation, friction);
}

}  // namespace softstep::scenes
