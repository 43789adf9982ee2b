// What every kernel of one sub-step needs to know besides its own lanes and the bodies.
#pragma once

#include <limits>

#include "softstep/simd/body_records.hpp"
#include "softstep/simd/softness.hpp"

namespace softstep::simd {

struct BodyArrays {
  VelocityRecord* velocity;
  const DeltaRecord* delta;
  const MassRecord* mass;
};

struct SubstepContext {
  float h;      // sub-step, s
  float inv_h;  // 1/h
  // Softness of rigid rows while solving (rigid rows use none while relaxing): a stiff spring
  // whose frequency is capped by the sub-step rate so it cannot overshoot.
  Softness<float> rigid;
  // Softness of a joint's violated axis or angle limit while solving (speculative while
  // ahead, no softness while relaxing): twice the rigid rows' frequency, capped at half the
  // sub-step rate (step.cpp, limit_solve_hertz, says why).
  Softness<float> limit;
  // Bound on the speed at which a rigid row corrects position error, m/s: a joint created far
  // apart is pulled together at this speed instead of launching its bodies.
  float max_correction_speed;
  // Bodies' speed bound, m/s (WorldSettings.max_linear_speed), applied as velocities are
  // integrated.
  float max_linear_speed;
  // The spin limit as an angular speed for this sub-step, rad/s:
  // WorldSettings.max_rotation_per_substep / h.
  float max_angular_speed;
};

// Spring frequency that marks a rigid row in kernel lanes (API: Spring::rigid()).
inline constexpr float kRigidHertz = std::numeric_limits<float>::infinity();

}  // namespace softstep::simd
