// Dual-axis part: two linear rows that keep B's anchor on A's axis, along A's frame axes x_A
// and y_A (perpendicular to the slide axis): C_i = t_i . d with d = anchor B - anchor A, and
// t_i turning with A, so (as for the slider's axis row, axis_part.hpp) the impulse on A acts at
// B's anchor (arm r_A + d). Rigid, solved as a 2x2 block. Used by the prismatic joint (and the
// wheel joint's lateral lock to come).
#pragma once

#include "softstep/simd/parts/axis_part.hpp"
#include "softstep/simd/parts/blocks.hpp"

namespace softstep::simd {

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_dual_axis(JointBodies<L>& j, const Vec3<L>& t1, const Vec3<L>& t2,
                                     float (&impulse)[2][kWidth<L>], const RowCoefficients<L>& co) {
  const Vec3<L> arm_a = j.r_a + j.separation;
  const Vec3<L> a1 = cross(arm_a, t1), a2 = cross(arm_a, t2);
  const Vec3<L> b1 = cross(j.r_b, t1), b2 = cross(j.r_b, t2);
  const Vec3<L> ia1 = j.a.inv_inertia * a1, ia2 = j.a.inv_inertia * a2;
  const Vec3<L> ib1 = j.b.inv_inertia * b1, ib2 = j.b.inv_inertia * b2;
  const L m_sum = j.a.inv_mass + j.b.inv_mass;
  const Mat2Sym<L> k{m_sum + dot(a1, ia1) + dot(b1, ib1), m_sum + dot(a2, ia2) + dot(b2, ib2),
                     dot(a1, ia2) + dot(b1, ib2)};
  const Vec3<L> dv = j.b.v - j.a.v;
  const Vec2<L> cdot{dot(t1, dv) + dot(j.b.w, b1) - dot(j.a.w, a1),
                     dot(t2, dv) + dot(j.b.w, b2) - dot(j.a.w, a2)};
  const Vec2<L> error{dot(t1, j.separation), dot(t2, j.separation)};
  const Vec2<L> accumulated{load<L>(impulse[0]), load<L>(impulse[1])};
  const Vec2<L> dp =
      block2_impulse<L, kUseBias>(cdot, error, k, inverse_or_zero(k), accumulated, co);
  store_lanes(impulse[0], accumulated.x + dp.x);
  store_lanes(impulse[1], accumulated.y + dp.y);
  apply_impulse_at(j, mul_add(dp.y, t2, dp.x * t1), arm_a, j.r_b);
}

template <class L>
SOFTSTEP_INLINE void warm_start_dual_axis(JointBodies<L>& j, const Vec3<L>& t1, const Vec3<L>& t2,
                                          const float (&impulse)[2][kWidth<L>]) {
  apply_impulse_at(j, mul_add(load<L>(impulse[1]), t2, load<L>(impulse[0]) * t1),
                   j.r_a + j.separation, j.r_b);
}

}  // namespace softstep::simd
