// How the angular joints name their axes. Each body carries a frame at the joint's anchor,
// given by two directions in the body's own frame: the joint's axis, and a reference
// direction perpendicular to it (only its part perpendicular to the axis counts). The joint
// is at rest, angle 0 and no twist, when both bodies' frames coincide in the world.
#pragma once

#include <Eigen/Core>

#include "softstep/ids.hpp"

namespace softstep {

class World;

struct JointFrame {
  Eigen::Vector3d local_anchor = Eigen::Vector3d::Zero();      // m, from the centre of mass
  Eigen::Vector3d local_axis = Eigen::Vector3d::UnitZ();       // any length > 0; normalized
  Eigen::Vector3d local_reference = Eigen::Vector3d::UnitX();  // not parallel to the axis
};

// The frames of a joint between a and b at a world point and a world axis, such that the
// bodies' pose now is the joint's rest pose (angle 0, translation 0, weld held as it is).
// Throws InvalidArgument for unknown bodies, a non-finite point or a zero axis.
struct JointFrames {
  JointFrame a, b;
};
JointFrames frames_at(const World& world, BodyId a, BodyId b, const Eigen::Vector3d& world_anchor,
                      const Eigen::Vector3d& world_axis);
// The same with a chosen reference (a wheel's axle); InvalidArgument also when it is zero or
// parallel to the axis.
JointFrames frames_at(const World& world, BodyId a, BodyId b, const Eigen::Vector3d& world_anchor,
                      const Eigen::Vector3d& world_axis, const Eigen::Vector3d& world_reference);

}  // namespace softstep
