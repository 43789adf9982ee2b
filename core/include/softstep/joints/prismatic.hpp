// Prismatic joint (slider: pistons, suspensions, lifts). B slides along A's axis and keeps
// its orientation relative to A. Parts, in order: the spring, the motor and the two limit
// rows along the axis (1 linear row each), 2 linear rows perpendicular to the axis, then 3
// angular rows that hold the relative rotation.
//
// The translation is (anchor B - anchor A) . axis of A, in m: 0 when the anchors coincide.
#pragma once

#include "softstep/ids.hpp"
#include "softstep/joints/axis_controls.hpp"
#include "softstep/joints/joint_frames.hpp"

namespace softstep {

struct PrismaticJointDef {
  BodyId body_a;
  BodyId body_b;
  JointFrame frame_a;  // anchor, slide axis and reference in A's frame
  JointFrame frame_b;
  AxisLimit limit;    // m
  LinearMotor motor;  // m/s, N
  AxisSpring spring;  // target translation, m
};

}  // namespace softstep
