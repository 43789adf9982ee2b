// Contacts made analytically for the tests: a box's face on a plane or on another box's top
// face, a sphere on a plane. No collision library: the geometry is simple enough to write
// exactly, which is what lets the tests compare with closed forms.
#pragma once

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::test {

// Half extents of the 1 m cubes most contact tests stack.
inline const Eigen::Vector3d kUnitCubeHalf(0.5, 0.5, 0.5);

// Settings for tests that watch the solver, not the sleep test.
inline WorldSettings settings_without_sleep() {
  WorldSettings s;
  s.sleeping = false;
  return s;
}

inline std::array<Eigen::Vector3d, 8> box_corners(const Eigen::Vector3d& half) {
  std::array<Eigen::Vector3d, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[static_cast<std::size_t>(i)] = {(i & 1) ? half.x() : -half.x(),
                                      (i & 2) ? half.y() : -half.y(),
                                      (i & 4) ? half.z() : -half.z()};
  }
  return c;
}

// The box's four lowest corners against the plane y = ground_top of a static body: normal +y
// from the ground (A) to the box (B), feature id = corner index.
inline ContactManifold box_on_ground(const World& world, BodyId ground, BodyId box,
                                     const Eigen::Vector3d& half, double ground_top = 0.0,
                                     double friction = 0.6) {
  const BodyState b = world.body(box);
  const BodyState g = world.body(ground);
  std::array<std::pair<double, int>, 8> heights;
  const auto corners = box_corners(half);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p = b.position + b.orientation * corners[static_cast<std::size_t>(i)];
    heights[static_cast<std::size_t>(i)] = {p.y(), i};
  }
  std::sort(heights.begin(), heights.end());
  ContactManifold m;
  m.body_a = ground;
  m.body_b = box;
  m.normal = Eigen::Vector3d::UnitY();
  m.friction = friction;
  m.point_count = 4;
  for (int k = 0; k < 4; ++k) {
    const int i = heights[static_cast<std::size_t>(k)].second;
    const Eigen::Vector3d p = b.position + b.orientation * corners[static_cast<std::size_t>(i)];
    ContactPoint& cp = m.points[static_cast<std::size_t>(k)];
    cp.anchor_b = corners[static_cast<std::size_t>(i)];
    cp.anchor_a =
        g.orientation.inverse() * (Eigen::Vector3d(p.x(), ground_top, p.z()) - g.position);
    cp.separation = p.y() - ground_top;
    cp.feature_id = static_cast<std::uint32_t>(i);
  }
  return m;
}

// The upper box's four bottom corners against the lower box's top face (boxes of the same
// size, stacked along y, nearly aligned): normal = the lower box's up axis, from lower (A) to
// upper (B).
inline ContactManifold box_on_box(const World& world, BodyId lower, BodyId upper,
                                  const Eigen::Vector3d& half, double friction = 0.6) {
  const BodyState a = world.body(lower);
  const BodyState b = world.body(upper);
  const auto corners = box_corners(half);
  ContactManifold m;
  m.body_a = lower;
  m.body_b = upper;
  m.normal = a.orientation * Eigen::Vector3d::UnitY();
  m.friction = friction;
  m.point_count = 4;
  int k = 0;
  for (int i = 0; i < 8; ++i) {
    if (i & 2) continue;  // bottom corners only
    const Eigen::Vector3d world_corner =
        b.position + b.orientation * corners[static_cast<std::size_t>(i)];
    const Eigen::Vector3d in_a = a.orientation.inverse() * (world_corner - a.position);
    ContactPoint& cp = m.points[static_cast<std::size_t>(k++)];
    cp.anchor_b = corners[static_cast<std::size_t>(i)];
    cp.anchor_a = {in_a.x(), half.y(), in_a.z()};
    cp.separation = in_a.y() - half.y();
    cp.feature_id = static_cast<std::uint32_t>(i);
  }
  return m;
}

// A sphere of radius r on the plane y = 0 of a static body: one point below the centre.
inline ContactManifold sphere_on_ground(const World& world, BodyId ground, BodyId ball, double r) {
  const BodyState b = world.body(ball);
  const BodyState g = world.body(ground);
  ContactManifold m;
  m.body_a = ground;
  m.body_b = ball;
  m.normal = Eigen::Vector3d::UnitY();
  m.friction = 0.0;
  m.point_count = 1;
  m.points[0].anchor_b = b.orientation.inverse() * Eigen::Vector3d(0.0, -r, 0.0);
  m.points[0].anchor_a =
      g.orientation.inverse() * (Eigen::Vector3d(b.position.x(), 0.0, b.position.z()) - g.position);
  m.points[0].separation = b.position.y() - r;
  return m;
}

// The same contact given as a round shape's (ContactManifold::radius_a / radius_b): the
// anchor is the sphere's centre and the radius puts its surface on the ground. With
// `ball_is_a` the pair is given the other way round (the ball is A, the normal points down
// to the ground), which exercises radius_a.
inline ContactManifold round_sphere_on_ground(const World& world, BodyId ground, BodyId ball,
                                              double r, bool ball_is_a = false) {
  ContactManifold m = sphere_on_ground(world, ground, ball, r);
  m.points[0].anchor_b = Eigen::Vector3d::Zero();
  m.radius_b = r;
  if (ball_is_a) {
    std::swap(m.body_a, m.body_b);
    std::swap(m.points[0].anchor_a, m.points[0].anchor_b);
    std::swap(m.radius_a, m.radius_b);
    m.normal = -m.normal;
  }
  return m;
}

inline BodyId add_box(World& world, const Eigen::Vector3d& position, double mass,
                      const Eigen::Vector3d& half) {
  BodyDef d;
  d.position = position;
  d.mass = mass;
  d.inertia = solid_box_inertia(mass, 2.0 * half);
  return world.create_body(d);
}

inline BodyId add_ground(World& world) {
  BodyDef d;
  d.type = BodyType::Static;
  return world.create_body(d);
}

}  // namespace softstep::test
