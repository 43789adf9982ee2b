// Semi-implicit Euler for the bodies (talk 1:2:2): velocities first, then positions from the
// new velocities. Positions advance as a displacement and a rotation since the step start;
// core adds them to the double-precision pose once per step.
#pragma once

#include <limits>

#include "softstep/simd/body_records.hpp"
#include "softstep/simd/step_context.hpp"

namespace softstep::simd {

// Forces a body feels during a step, precomputed so that a body with none costs nothing
// beyond being skipped (core does not list it for this pass).
struct alignas(32) ForceRecord {
  // m/s^2: world gravity times the body's gravity scale, plus any applied force / mass
  float gravity[3];
  float linear_damping;           // 1/(1 + h c_linear), 1 = none
  float angular_damping;          // 1/(1 + h c_angular), 1 = none
  float angular_acceleration[3];  // rad/s^2, world frame: inverse inertia x applied torque
};

template <class L>
SOFTSTEP_INLINE L squared_norm(const L& x, const L& y, const L& z) {
  return fmadd(x, x, fmadd(y, y, z * z));
}

// Scales (x, y, z) down to length `limit` where it is longer; lanes within it are untouched,
// bit for bit.
template <class L>
SOFTSTEP_INLINE void clamp_norm(L& x, L& y, L& z, L limit) {
  const L n2 = squared_norm(x, y, z);
  const auto over = n2 > limit * limit;
  L scale = select(over, limit / sqrt_lanes(select(over, n2, L(1.0f))), L(1.0f));
  // Above ~1.8e19 the square overflows and that scale is 0, which stops a body the solve threw
  // hard instead of slowing it along its direction. There the norm is taken of the vector
  // scaled by 2^-66 (exact, and no square of a float can overflow after it); a lane with an
  // infinite component still ends NaN, as it would anyway.
  const L infinity(std::numeric_limits<float>::infinity());
  const auto overflowed = n2 == infinity;
  if (any_lane(overflowed)) {
    const L tiny(0x1p-66f);
    const L scaled_n2 = squared_norm(x * tiny, y * tiny, z * tiny);
    scale = select(overflowed, (limit * tiny) / sqrt_lanes(scaled_n2), scale);
  }
  x = x * scale;
  y = y * scale;
  z = z * scale;
}

// Bodies [first, first + W) at once: records are contiguous, so the "gather" is W aligned
// loads and a transpose. Callers pass whole blocks; slots of static bodies, free slots and
// sleeping bodies hold zero velocity, no force and an identity rotation, which integrate to
// themselves exactly.
// kGravity, kDamping, kTorque: compiled out when no body of the step has any (a gravity of 0,
// a damping factor of 1 and no torque give the same velocities: v + h 0 = v, v 1 = v). Applied
// forces ride on the gravity term (force / mass), applied torques on kTorque.
template <class L, bool kGravity = true, bool kDamping = true, bool kTorque = false>
SOFTSTEP_INLINE void integrate_velocities(VelocityRecord* velocity, const ForceRecord* force,
                                          std::int32_t first, const SubstepContext& ctx) {
  const float h = ctx.h;
  std::int32_t index[kWidth<L>];
  for (int i = 0; i < kWidth<L>; ++i) index[i] = first + i;
  Rows8<L> v = gather_rows<L>(velocity, index);
  if constexpr (kGravity || kDamping || kTorque) {
    const Rows8<L> f = gather_rows<L>(force, index);
    for (int k = 0; k < 3; ++k) {
      if constexpr (kGravity) v.r[k] = fmadd(L(h), f.r[k], v.r[k]);
      if constexpr (kTorque) v.r[k + 3] = fmadd(L(h), f.r[k + 5], v.r[k + 3]);
      if constexpr (kDamping) {
        v.r[k] = v.r[k] * f.r[3];
        v.r[k + 3] = v.r[k + 3] * f.r[4];
      }
    }
  }
  // A body may turn at most max_rotation_per_substep per sub-step (default an eighth of a
  // turn). Beyond it the first-order rotation update is meaningless and a joint anchored off
  // the centre swings its anchor anywhere: links with tiny inertia and chains at 1/15 s steps
  // exploded (energy x 1e7) before this bound.
  clamp_norm(v.r[3], v.r[4], v.r[5], L(ctx.max_angular_speed));
  // The speed bound keeps the kernels' float products in range (validation.cpp).
  clamp_norm(v.r[0], v.r[1], v.r[2], L(ctx.max_linear_speed));
  scatter_rows<L>(velocity, index, v, L(0.0f) == L(0.0f));
}

// The speed and spin limits bind again here, after the solve: rows that cannot all hold (a
// motor driving against a rigid joint, a joint to a kinematic body whirling its anchor at
// 30 km/s), softened so that the warm start carries large impulses, pushed a light body's
// velocity past the limits in the solve, and positions moving at that speed grew it 10x a
// step to NaN. The clamped velocity is stored (the relax pass starts from it), only where a
// lane was clamped: the store costs as much as the rest of this pass.
template <class L>
SOFTSTEP_INLINE void integrate_positions(DeltaRecord* delta, VelocityRecord* velocity,
                                         std::int32_t first, const SubstepContext& ctx) {
  std::int32_t index[kWidth<L>];
  for (int i = 0; i < kWidth<L>; ++i) index[i] = first + i;
  Rows8<L> v = gather_rows<L>(velocity, index);
  const L linear_limit(ctx.max_linear_speed), angular_limit(ctx.max_angular_speed);
  if (any_lane(squared_norm(v.r[0], v.r[1], v.r[2]) > linear_limit * linear_limit ||
               squared_norm(v.r[3], v.r[4], v.r[5]) > angular_limit * angular_limit)) {
    clamp_norm(v.r[3], v.r[4], v.r[5], angular_limit);
    clamp_norm(v.r[0], v.r[1], v.r[2], linear_limit);
    scatter_rows<L>(velocity, index, v, L(0.0f) == L(0.0f));
  }
  Rows8<L> d = gather_rows<L>(delta, index);
  const L hl(ctx.h);
  for (int k = 0; k < 3; ++k) d.r[k] = fmadd(hl, v.r[k], d.r[k]);
  const Quat<L> q = integrate_rotation(Quat<L>{d.r[3], d.r[4], d.r[5], d.r[6]},
                                       Vec3<L>{v.r[3], v.r[4], v.r[5]}, hl);
  d.r[3] = q.x;
  d.r[4] = q.y;
  d.r[5] = q.z;
  d.r[6] = q.w;
  scatter_rows<L>(delta, index, d, L(0.0f) == L(0.0f));
}

}  // namespace softstep::simd
