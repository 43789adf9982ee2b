// A sphere's contact with a plane and with an oriented box, computed analytically: the narrow
// phase of the scenes whose only round shapes are wheels (vehicle, the cart crossing the
// suspension bridge). One point per pair, so feature id 0 and key 0 identify it from step to
// step (a body pair has one manifold) and warm starting carries its impulses over; the point
// stays the same feature when the closest point slides from a box's face to its edge. The
// sphere's side is given as round (anchor_b its centre, radius_b its radius), so a fast-rolling
// wheel's contact stays at the bottom within the step.
//
// A wheel is a sphere here: with its axle level (the wheel joint keeps it so) a cylinder's
// lowest point is the sphere's, straight below the centre; a rolled axle would put the
// cylinder's point on its rim's edge, which the sphere ignores.
#pragma once

#include <optional>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct SphereShape {
  BodyId body;
  double radius = 0.0;  // m
};

// The sphere on the plane y = height (world) of a static or kinematic body `ground`: one point
// below the centre, normal +y from the ground (A) to the sphere (B). None when the sphere is
// more than `margin` above the plane (within it the point is speculative).
std::optional<ContactManifold> sphere_on_plane(const World& world, BodyId ground, double height,
                                               const SphereShape& sphere, double margin,
                                               double friction);

// The sphere against the box of half extents `half` centred on `box`'s centre of mass, along
// its axes: the box's point closest to the sphere's centre, normal from that point to the
// centre (the box is A); with the centre inside the box, the face it is nearest to. None when
// the gap exceeds `margin`.
std::optional<ContactManifold> sphere_on_box(const World& world, BodyId box,
                                             const Eigen::Vector3d& half,
                                             const SphereShape& sphere, double margin,
                                             double friction);

}  // namespace softstep::scenes
