// Wheel joint (a car's wheel on its suspension): A is the chassis, B the wheel. The wheel's
// centre slides along the chassis's suspension axis, held by a spring (hertz, damping ratio)
// and optionally by travel limits; it cannot move sideways or forwards relative to the
// chassis (2 linear rows); its axle stays on the chassis's axle, turned by the steering angle
// about the suspension axis (2 angular rows); it spins freely about the axle, or driven by a
// motor (target speed, max torque).
//
// Frames (joint_frames.hpp): frame_a's axis is the suspension axis (travel is positive along
// it, usually up), its reference the axle at zero steering, its anchor the wheel's centre at
// zero travel. frame_b's reference is the wheel's axle in the wheel's frame and its anchor the
// wheel's centre; its axis is any direction perpendicular to the axle (it spins with the
// wheel). frames_at(world, chassis, wheel, centre, suspension_axis, axle) builds both.
//
// Which mass the spring's frequency refers to: `sprung_mass`, the part of the chassis this
// wheel carries (a 1,200 kg car on four wheels: 300 kg each). The spring's stiffness and
// damping are k = sprung_mass (2 pi hertz)^2 and c = 2 sprung_mass damping_ratio (2 pi hertz),
// so the car bounces at `hertz` with `damping_ratio` whatever its wheels weigh. (The row's own
// effective mass is dominated by the light wheel: a frequency relative to it would give a far
// softer spring, and the car would sink.) A soft spring needs sprung_mass in [1e-9, 1e9] kg (a
// body's smallest mass: below it the float spring overflows), unless it is
// given in absolute units: Spring::absolute(k, c) in N/m and N s/m is the chassis's spring
// itself (sprung_mass is then unused, >= 0), the same path and the same damping correction
// as k = sprung_mass omega^2, c = 2 sprung_mass zeta omega (wheel_joint_kernel.hpp). The spring's
// target is the travel at which it is unloaded: under gravity g the car rides g / (2 pi
// hertz)^2 below it.
//
// Steering is set at run time with set_joint (changing only `steering`, or the motor's speed,
// refreshes the joint's lane without re-packing the world).
#pragma once

#include "softstep/ids.hpp"
#include "softstep/joints/axis_controls.hpp"
#include "softstep/joints/joint_frames.hpp"

namespace softstep {

struct WheelJointDef {
  BodyId body_a;       // the chassis
  BodyId body_b;       // the wheel
  JointFrame frame_a;  // suspension axis, axle at zero steering, wheel centre at zero travel
  JointFrame frame_b;  // the wheel's axle (reference) and centre (anchor)
  AxisSpring spring;   // suspension; target: the unloaded travel, m
  double sprung_mass = 0.0;  // kg the spring carries, >= 1e-9 when the spring is soft
  AxisLimit limit;           // travel, m
  AngularMotor motor;        // spin of the wheel about the axle relative to the chassis, rad/s
  double steering = 0.0;     // rad, the axle turned about the suspension axis (right-handed)
};

}  // namespace softstep
