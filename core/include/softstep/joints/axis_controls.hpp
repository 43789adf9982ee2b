// What a joint may do along or about its one free axis (a hinge's angle, a slider's
// translation): a limit, a motor and a spring. Shared by the revolute and prismatic joints
// (and the wheel joint to come). Positions are angles in rad about a hinge, lengths in m along
// a slider; each setting is off until enabled, and a joint runs no row for what is off.
#pragma once

#include "softstep/spring.hpp"

namespace softstep {

// Keeps the position within [lower, upper]: two one-sided rigid rows, speculative while the
// position is inside (a fast body is stopped at the limit, not after it). lower == upper
// locks the axis.
struct AxisLimit {
  bool enabled = false;
  double lower = 0.0;  // rad or m, <= upper
  double upper = 0.0;  // rad or m
};

// Drives the axis towards a relative speed with at most a given torque (hinge) ...
struct AngularMotor {
  bool enabled = false;
  double speed = 0.0;       // rad/s of B relative to A about the axis
  double max_torque = 0.0;  // N m, >= 0
};

// ... or force (slider).
struct LinearMotor {
  bool enabled = false;
  double speed = 0.0;      // m/s of B relative to A along the axis
  double max_force = 0.0;  // N, >= 0
};

// Pulls the position towards `target` like a damped spring of the given frequency, felt by
// the effective mass the axis row sees (as every Spring in softstep). Soft or free (the
// default: no spring); a rigid spring is rejected (lock the axis with a limit instead).
// Or in absolute units, Spring::absolute(k, c): N m/rad and N m s/rad on a revolute joint's
// angle, N/m and N s/m on a prismatic joint's or a wheel's travel; the solver converts with
// the row's effective mass in each sub-step (JointReading::effective_mass reads it).
struct AxisSpring {
  Spring spring = Spring::free();
  double target = 0.0;  // rad or m
};

}  // namespace softstep
