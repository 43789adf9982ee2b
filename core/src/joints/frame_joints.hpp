// What the angular kinds (revolute, prismatic, weld) share on the core side: joint frames
// from the public JointFrame, their validation, the step-start frames for the lanes, hinge
// angles kept unwrapped, and the lanes of a free axis's limit, motor and spring.
#pragma once

#include "joints/joint_common.hpp"
#include "softstep/joints/axis_controls.hpp"
#include "softstep/joints/joint_frames.hpp"
#include "softstep/simd/frame_lanes.hpp"

namespace softstep {

// The frame's rotation in its body: columns x = reference (made perpendicular to the axis),
// y = axis x reference, z = axis.
Quaternion frame_rotation(const JointFrame& frame);

// The frame with its axis normalized and its reference made a unit vector perpendicular to
// the axis; InvalidArgument for a non-finite or zero axis or a reference parallel to it.
JointFrame checked_frame(std::string_view call, const std::string& field, const JointFrame& frame);

// The slot's ends and anchors from two frames (checked_joint_ends + checked_frame).
JointSlot checked_frame_ends(const World::Impl& w, std::string_view call, std::string_view def,
                             BodyId a, BodyId b, JointFrame& frame_a, JointFrame& frame_b);

// The frames in the world now, from the double poses.
struct WorldFrames {
  Quaternion a, b;
};
WorldFrames world_frames(const World::Impl& w, const JointSlot& j, const JointFrame& frame_a,
                         const JointFrame& frame_b);
WorldFrames world_frames(const BodySlot& a, const BodySlot& b, const JointFrame& frame_a,
                         const JointFrame& frame_b);

// The hinge angle of two world frames: B's turn about A's z, in (-pi, pi].
double wrapped_hinge_angle(const WorldFrames& f);
// `wrapped` (in (-pi, pi]) moved by whole turns to within half a turn of `previous`.
double unwrap_angle(double previous, double wrapped);

template <int W>
void write_frame_lanes(simd::FrameLanes<W>& g, int lane, const WorldFrames& f) {
  const auto put = [&](float(&q)[4][W], const Quaternion& v) {
    q[0][lane] = static_cast<float>(v.x());
    q[1][lane] = static_cast<float>(v.y());
    q[2][lane] = static_cast<float>(v.z());
    q[3][lane] = static_cast<float>(v.w());
  };
  put(g.frame_a, f.a);
  put(g.frame_b, f.b);
}

// Checks of a free axis's controls ("RevoluteJointDef.limit.lower", ...).
void check_axis_limit(std::string_view call, const std::string& field, const AxisLimit& limit);
void check_motor(std::string_view call, const std::string& field, double speed, double max,
                 const char* max_name);
void check_axis_spring(std::string_view call, const std::string& field, const AxisSpring& spring);

// The axis controls' part of a signature (simd::kAxisLimit, kAxisMotor, kAxisSpring).
std::uint32_t axis_signature(const AxisLimit& limit, bool motor, const AxisSpring& spring);
// "limit + motor + spring" for the plan.
std::string axis_parts(std::uint32_t signature);
// The rows the axis controls of a signature add (limit: lower and upper, motor, spring).
int axis_control_rows(std::uint32_t signature);

// Where the axis controls' impulses sit in a slot's impulse block (after the locks).
inline constexpr int kAxisImpulses = 5;  // lower, upper, motor, spring at [5..8]

template <int W>
void fill_axis_controls(simd::AxisControlLanes<W>& g, int lane, const AxisLimit& limit,
                        double motor_speed, double motor_max, const AxisSpring& spring,
                        const JointSlot& j) {
  g.motor_speed[lane] = static_cast<float>(motor_speed);
  g.motor_max[lane] = static_cast<float>(motor_max);
  g.spring_hertz[lane] = static_cast<float>(spring.spring.hertz);  // 0 when absolute
  g.spring_zeta[lane] = static_cast<float>(spring.spring.damping_ratio);
  g.spring_stiffness[lane] = static_cast<float>(spring.spring.absolute_stiffness);  // 0 if relative
  g.spring_damping[lane] = static_cast<float>(spring.spring.absolute_damping);
  g.lower_impulse[lane] = j.impulse[kAxisImpulses];
  g.upper_impulse[lane] = j.impulse[kAxisImpulses + 1];
  g.motor_impulse[lane] = j.impulse[kAxisImpulses + 2];
  g.spring_impulse[lane] = j.impulse[kAxisImpulses + 3];
  (void)limit;
}

// The gaps at the step start for a position `start` the kernel measures from (revolute: the
// unwrapped angle, the kernel adding the change within the step; prismatic: 0, the kernel
// measuring the whole translation).
template <int W>
void write_axis_gaps(simd::AxisControlLanes<W>& g, int lane, double start, const AxisLimit& limit,
                     const AxisSpring& spring) {
  g.lower_gap[lane] = static_cast<float>(start - limit.lower);
  g.upper_gap[lane] = static_cast<float>(limit.upper - start);
  g.spring_gap[lane] = static_cast<float>(start - spring.target);
}

template <int W>
void read_axis_impulses(const simd::AxisControlLanes<W>& g, int lane, float* out) {
  out[kAxisImpulses] = g.lower_impulse[lane];
  out[kAxisImpulses + 1] = g.upper_impulse[lane];
  out[kAxisImpulses + 2] = g.motor_impulse[lane];
  out[kAxisImpulses + 3] = g.spring_impulse[lane];
}

// The effective mass of a slider row along unit `axis` now (prismatic, wheel: the arms of
// axis_part.hpp, B's anchor from each centre), for JointReading::effective_mass.
double slider_effective_mass(const World::Impl& w, const JointSlot& j, const WorldAnchors& anchors,
                             const Eigen::Vector3d& axis);

// The axis controls' impulses into a reading; returns their sum along the axis.
double read_axis_controls(const float* impulse, JointReading& r);

// The limit, motor and spring settings into the state hash.
void hash_axis_controls(StateHasher& h, const AxisLimit& limit, bool motor_enabled,
                        double motor_speed, double motor_max, const AxisSpring& spring);
void hash_frame(StateHasher& h, const JointFrame& f);

}  // namespace softstep
