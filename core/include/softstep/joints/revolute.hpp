// Revolute joint (hinge: doors, elbows, knees, wheels on an axle). Parts, solved in this
// order: the spring, the motor and the two limit rows about the axis (1 angular row each),
// then 2 angular rows that keep the axes parallel, then the point (3 linear rows).
//
// The angle is B's turn relative to A about A's axis, from A's reference to B's reference,
// right-handed. It is continuous across +-pi: the world keeps it unwrapped in double and adds,
// each step, the change since the last one. So a motor can spin a wheel for ever and a limit
// of +-170 degrees (or +-3 turns) works. The change per step must stay under half a turn
// (188 rad/s of relative spin at 60 Hz), beyond what the spin limit lets a body reach.
#pragma once

#include "softstep/ids.hpp"
#include "softstep/joints/axis_controls.hpp"
#include "softstep/joints/joint_frames.hpp"

namespace softstep {

struct RevoluteJointDef {
  BodyId body_a;
  BodyId body_b;
  JointFrame frame_a;  // anchor, hinge axis and zero-angle reference in A's frame
  JointFrame frame_b;
  AxisLimit limit;     // rad
  AngularMotor motor;  // rad/s, N m
  AxisSpring spring;   // target angle, rad
};

}  // namespace softstep
