// Motor joint: drives body B towards a target pose relative to body A, with at most
// max_force and max_torque (animation-driven ragdolls, dragging a body with the mouse). Two
// halves, each with its own correction: the rotation (3 angular rows) turning B's frame onto
// A's, then the point (3 linear rows) bringing B's anchor onto A's. A rigid half drives B at
// up to the world's max_correction_speed; a soft one like a spring of the given frequency and damping ratio,
// felt by the effective mass its rows see. Either way the impulse a half applies in a sub-step
// is at most max_force (or max_torque) times the sub-step, in length.
//
// The target is frame_a: set it at run time with set_joint (changing only frames or caps
// refreshes the joint's lane without re-packing the world). For mouse dragging, A is a static
// body and frame_a.local_anchor the mouse point; frame_b's anchor is the grabbed point of B.
#pragma once

#include "softstep/ids.hpp"
#include "softstep/joints/joint_frames.hpp"
#include "softstep/spring.hpp"

namespace softstep {

struct MotorJointDef {
  BodyId body_a;
  BodyId body_b;
  JointFrame frame_a;  // the target pose of B's frame, in A's frame
  JointFrame frame_b;  // the frame of B that is driven
  double max_force = 0.0;   // N, >= 0
  double max_torque = 0.0;  // N m, >= 0
  Spring linear = Spring::rigid();   // rigid or soft (not free: a zero cap leaves a half idle)
  Spring angular = Spring::rigid();  // rigid or soft
};

}  // namespace softstep
