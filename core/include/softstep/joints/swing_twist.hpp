// Swing-twist joint (ragdoll shoulders, hips, necks): B's anchor held on A's (a ball joint),
// with B's orientation limited as a joint of the body is. Each frame's axis (JointFrame, z) is
// the twist axis: the limb's length for a shoulder or hip, the spine's for a neck.
//
// How the relative rotation is split: q = frame_A^-1 frame_B = q_swing * q_twist, where
// q_twist turns about z and q_swing about an axis in A's xy plane, taking A's twist axis to
// B's the short way. So
//   swing = the angle between the two twist axes, in [0, pi]; its direction is where B's axis
//           leans in A's frame (towards A's x, the reference, or y = axis x reference);
//   twist = 2 atan2(q.z, q.w), in (-pi, pi]: B's turn about its own axis, as seen after
//           undoing the swing. It does not change when B only swings, and the swing does not
//           change when B only twists, so each limit holds whatever the other angle is.
// Near a 180-degree swing the twist is undefined (q.z and q.w both go to zero): the twist
// limit rows weaken as cos^2(swing/2) (their Jacobian grows as 1/cos(swing/2)) and are off
// beyond about 177 degrees of swing; the point and the cone still hold. Keep cones below
// about 170 degrees when the twist limit matters.
//
// Parts, solved in this order: the orientation spring (3 soft rows), the friction motor (3
// rows), the twist limit (2 one-sided rows), the swing cone (1 one-sided row), then the point
// (3 rigid rows). Limits are rigid one-sided rows, speculative while inside (a fast limb stops
// at the edge, not after it), and each part runs only when enabled.
#pragma once

#include "softstep/eigen_types.hpp"
#include "softstep/ids.hpp"
#include "softstep/joints/axis_controls.hpp"
#include "softstep/joints/joint_frames.hpp"
#include "softstep/spring.hpp"

namespace softstep {

// The cone B's twist axis stays in, about A's twist axis: an ellipse of half-angles
// half_angle_x (leaning towards A's reference x) and half_angle_y (towards A's y). Equal
// half-angles make a circular cone. Each in [1e-6, pi] (a narrower cone is a fixed swing).
struct SwingCone {
  bool enabled = false;
  double half_angle_x = 0.0;  // rad
  double half_angle_y = 0.0;  // rad
};

// Pulls B's frame towards A's frame turned by `target` (the relative rotation wanted: identity
// = the frames coincide), about every axis, as a damped spring of the given frequency felt by
// the effective inertia the rows see. Soft or free (the default); rigid is rejected (a weld).
struct OrientationSpring {
  Spring spring = Spring::free();
  Quaternion target = Quaternion::Identity();  // any non-zero length; normalized
};

// Joint friction: resists the relative angular velocity with at most max_torque, about any
// axis (a ragdoll's muscles at rest: limbs settle instead of swinging for ever).
struct FrictionMotor {
  bool enabled = false;
  double max_torque = 0.0;  // N m, >= 0
};

struct SwingTwistJointDef {
  BodyId body_a;
  BodyId body_b;
  JointFrame frame_a;  // anchor, twist axis and reference (where the swing's x points), in A
  JointFrame frame_b;
  SwingCone cone;
  AxisLimit twist;  // rad, within [-pi, pi]
  OrientationSpring spring;
  FrictionMotor motor;
};

}  // namespace softstep
