// A revolute, prismatic or weld definition between a and b at a world point and axis, with
// the bodies' pose now as its rest pose (frames_at): the usual first line of a joint. Limits,
// motors and springs are left off for the caller to set.
#pragma once

#include "softstep/softstep.hpp"

namespace softstep::scenes {

template <class Def>
Def joint_at(const World& world, BodyId a, BodyId b, const Eigen::Vector3d& world_point,
             const Eigen::Vector3d& world_axis) {
  const JointFrames frames = frames_at(world, a, b, world_point, world_axis);
  Def def;
  def.body_a = a;
  def.body_b = b;
  def.frame_a = frames.a;
  def.frame_b = frames.b;
  return def;
}

}  // namespace softstep::scenes
