// Angular parts: rows whose Jacobian is purely angular, J v = u . (w_B - w_A), so that
// K = u . (I_A^-1 + I_B^-1) u, and whose impulse is a torque (apply_angular_impulse).
//
// angular lock, 3 rows (weld, prismatic): C = rotation_error(frame A, frame B) (angles.hpp),
//   the rows are the world axes, J = [-1, 1]: exact at zero error, where a lock lives.
// angular lock, 2 rows (hinge: keep B's axis a_B along A's axis, the frame's z):
//   C_1 = -a_B . y_A,  u_1 = y_A x a_B;   C_2 = a_B . x_A,  u_2 = a_B x x_A
//   (the exact derivatives: d/dt (a_B . y_A) = (a_B x y_A) . (w_B - w_A)).
// angular axis, 1 row about a unit axis a (a hinge's limit, motor and spring):
//   C = the hinge angle (minus a limit or target), u = a.
// Solved as blocks (blocks.hpp) for the locks, by rows.hpp's modes for the axis row.
#pragma once

#include "softstep/simd/angles.hpp"
#include "softstep/simd/parts/blocks.hpp"

namespace softstep::simd {

template <class L>
SOFTSTEP_INLINE Vec3<L> relative_angular_velocity(const JointBodies<L>& j) {
  return j.b.w - j.a.w;
}

// ---- angular lock, 3 rows ------------------------------------------------------------------

template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE void solve_angular_lock3(JointBodies<L>& j, const Vec3<L>& error,
                                         float (&impulse)[3][kWidth<L>],
                                         const RowCoefficients<L>& co) {
  const Mat3Sym<L> k = j.a.inv_inertia + j.b.inv_inertia;
  const Mat3Sym<L> k_inv = inverse_or_zero(k);
  const Vec3<L> accumulated = load3<L>(impulse);
  const Vec3<L> dp = block3_impulse<L, kUseBias, kRow>(relative_angular_velocity(j), error, k,
                                                       k_inv, accumulated, co);
  store3<L>(impulse, accumulated + dp);
  apply_angular_impulse(j, dp);
}

// ---- angular lock, 2 rows (hinge) ------------------------------------------------------------

template <class L>
struct HingeLock {
  Vec3<L> u1, u2;
  Vec2<L> error;
};

// From A's frame axes x_a, y_a and B's hinge axis a_b (all world, unit).
template <class L>
SOFTSTEP_INLINE HingeLock<L> hinge_lock(const Vec3<L>& x_a, const Vec3<L>& y_a,
                                        const Vec3<L>& a_b) {
  return {cross(y_a, a_b), cross(a_b, x_a), {L(0.0f) - dot(a_b, y_a), dot(a_b, x_a)}};
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_hinge_lock(JointBodies<L>& j, const HingeLock<L>& h,
                                      float (&impulse)[2][kWidth<L>],
                                      const RowCoefficients<L>& co) {
  const Mat3Sym<L> inv_i = j.a.inv_inertia + j.b.inv_inertia;
  const Vec3<L> i_u1 = inv_i * h.u1;
  const Vec3<L> i_u2 = inv_i * h.u2;
  const Mat2Sym<L> k{dot(h.u1, i_u1), dot(h.u2, i_u2), dot(h.u1, i_u2)};
  const Vec3<L> dw = relative_angular_velocity(j);
  const Vec2<L> accumulated{load<L>(impulse[0]), load<L>(impulse[1])};
  // A row's error is the sine of B's axis leaning, and |u| its cosine: a row that asked
  // max_correction_speed of its error turned B at max_correction_speed / |u|, without bound
  // as B's axis nears 90 degrees from A's, where u is float rounding (B spun from 1e-5 to 3e9
  // rad/s in one solve, or the impulse left float: a corner sampler's revolute and wheel
  // joints created with their axes crossed). So each row's correction is bounded by
  // max_correction_speed |u|: the lean closes at that speed (Revolute.AxesCreatedCrossed-
  // CloseAtTheCorrectionSpeed). Within ~0.01 degrees of crossed the impulse such a row
  // accumulates, ~1 / |u|, still turns B fast when warm-started along a longer row.
  // Normalizing the rows would bound that too, and move every hinge's bits.
  Vec2<L> bound_scale{L(1.0f), L(1.0f)};
  if constexpr (kUseBias) {
    bound_scale = {sqrt_lanes(dot(h.u1, h.u1)), sqrt_lanes(dot(h.u2, h.u2))};
  }
  const Vec2<L> dp = block2_impulse<L, kUseBias>(Vec2<L>{dot(h.u1, dw), dot(h.u2, dw)}, h.error, k,
                                                 inverse_or_zero(k), accumulated, co, bound_scale);
  store_lanes(impulse[0], accumulated.x + dp.x);
  store_lanes(impulse[1], accumulated.y + dp.y);
  apply_angular_impulse(j, mul_add(dp.y, h.u2, dp.x * h.u1));
}

template <class L>
SOFTSTEP_INLINE void warm_start_hinge_lock(JointBodies<L>& j, const HingeLock<L>& h,
                                           const float (&impulse)[2][kWidth<L>]) {
  apply_angular_impulse(j, mul_add(load<L>(impulse[1]), h.u2, load<L>(impulse[0]) * h.u1));
}

// ---- angular axis, 1 row -------------------------------------------------------------------

template <class L>
struct AngularAxis {
  Vec3<L> a;
  L k, m_eff;
  L cdot;  // a . (w_B - w_A), refreshed by the caller after each row it applies
};

template <class L>
SOFTSTEP_INLINE AngularAxis<L> angular_axis(const JointBodies<L>& j, const Vec3<L>& a) {
  const L k = dot(a, (j.a.inv_inertia + j.b.inv_inertia) * a);
  return {a, k, inverse_or_zero(k), dot(a, relative_angular_velocity(j))};
}

template <class L>
SOFTSTEP_INLINE void apply_axis_torque(JointBodies<L>& j, AngularAxis<L>& axis, const L& impulse) {
  apply_angular_impulse(j, impulse * axis.a);
  axis.cdot = dot(axis.a, relative_angular_velocity(j));
}

}  // namespace softstep::simd
