// Semi-implicit Euler for the bodies (talk 1:2:2): velocities first, then positions from the
// new velocities. Positions advance as a displacement and a rotation since the step start;
// core adds them to the double-precision pose once per step.
#pragma once

#include "softstep/simd/body_records.hpp"

namespace softstep::simd {

// Forces a body feels during a step, precomputed so that a body with none costs nothing
// beyond being skipped (core does not list it for this pass).
struct alignas(32) ForceRecord {
  float gravity[3];       // m/s^2, world gravity times the body's gravity scale
  float linear_damping;   // 1/(1 + h c_linear), 1 = none
  float angular_damping;  // 1/(1 + h c_angular), 1 = none
  float unused[3];
};

inline void integrate_velocity(VelocityRecord& b, const ForceRecord& f, float h) {
  for (int k = 0; k < 3; ++k) {
    b.v[k] = fmadd(h, f.gravity[k], b.v[k]) * f.linear_damping;
    b.w[k] = b.w[k] * f.angular_damping;
  }
}

inline void integrate_position(DeltaRecord& d, const VelocityRecord& b, float h) {
  for (int k = 0; k < 3; ++k) d.dp[k] = fmadd(h, b.v[k], d.dp[k]);
  const Quat<float> q = integrate_rotation(Quat<float>{d.dq[0], d.dq[1], d.dq[2], d.dq[3]},
                                           Vec3<float>{b.w[0], b.w[1], b.w[2]}, h);
  d.dq[0] = q.x;
  d.dq[1] = q.y;
  d.dq[2] = q.z;
  d.dq[3] = q.w;
}

}  // namespace softstep::simd
