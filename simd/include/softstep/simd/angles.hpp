// Rotations between joint frames: quaternion products, the frame's axes, and angles. Written
// with the lane vocabulary only (our own arctangent included: libm's and xsimd's differ in
// their last bits, and every width must agree bit for bit).
#pragma once

#include <numbers>

#include "softstep/simd/math3.hpp"

namespace softstep::simd {

template <class L>
SOFTSTEP_INLINE Quat<L> multiply(const Quat<L>& a, const Quat<L>& b) {
  return {fmadd(a.w, b.x, fmadd(a.x, b.w, fmadd(a.y, b.z, L(0.0f) - a.z * b.y))),
          fmadd(a.w, b.y, fmadd(a.y, b.w, fmadd(a.z, b.x, L(0.0f) - a.x * b.z))),
          fmadd(a.w, b.z, fmadd(a.z, b.w, fmadd(a.x, b.y, L(0.0f) - a.y * b.x))),
          fmadd(a.w, b.w, L(0.0f) - fmadd(a.x, b.x, fmadd(a.y, b.y, a.z * b.z)))};
}

template <class L>
SOFTSTEP_INLINE Quat<L> conjugate(const Quat<L>& q) {
  return {L(0.0f) - q.x, L(0.0f) - q.y, L(0.0f) - q.z, q.w};
}

// The same rotation with w >= 0 (q and -q are one rotation; angles below want the short way).
template <class L>
SOFTSTEP_INLINE Quat<L> short_way(const Quat<L>& q) {
  const L s = select(q.w < L(0.0f), L(-1.0f), L(1.0f));
  return {s * q.x, s * q.y, s * q.z, s * q.w};
}

// The columns of q's rotation matrix: where q turns the unit x, y and z axes.
template <class L>
SOFTSTEP_INLINE Vec3<L> axis_x(const Quat<L>& q) {
  return {L(1.0f) - L(2.0f) * fmadd(q.y, q.y, q.z * q.z), L(2.0f) * fmadd(q.x, q.y, q.w * q.z),
          L(2.0f) * fmadd(q.x, q.z, L(0.0f) - q.w * q.y)};
}
template <class L>
SOFTSTEP_INLINE Vec3<L> axis_y(const Quat<L>& q) {
  return {L(2.0f) * fmadd(q.x, q.y, L(0.0f) - q.w * q.z),
          L(1.0f) - L(2.0f) * fmadd(q.x, q.x, q.z * q.z), L(2.0f) * fmadd(q.y, q.z, q.w * q.x)};
}
template <class L>
SOFTSTEP_INLINE Vec3<L> axis_z(const Quat<L>& q) {
  return {L(2.0f) * fmadd(q.x, q.z, q.w * q.y), L(2.0f) * fmadd(q.y, q.z, L(0.0f) - q.w * q.x),
          L(1.0f) - L(2.0f) * fmadd(q.x, q.x, q.y * q.y)};
}

// atan(t), float accuracy (within 2 ulp): the reduction to |t| <= tan(pi/8) and the odd
// polynomial of Cephes' atanf (S. Moshier), here in lanes.
template <class L>
SOFTSTEP_INLINE L atan_lanes(const L& t) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const auto negative = t < L(0.0f);
  const L x = select(negative, L(0.0f) - t, t);
  const auto big = x > L(2.414213562373095f);      // tan(3 pi / 8)
  const auto middle = x > L(0.4142135623730950f);  // tan(pi / 8)
  const L safe_x = select(big, x, L(1.0f));
  const L reduced =
      select(big, L(-1.0f) / safe_x, select(middle, (x - L(1.0f)) / (x + L(1.0f)), x));
  const L offset = select(big, L(0.5f * kPi), select(middle, L(0.25f * kPi), L(0.0f)));
  const L z = reduced * reduced;
  L p = fmadd(L(8.05374449538e-2f), z, L(-1.38776856032e-1f));
  p = fmadd(p, z, L(1.99777106478e-1f));
  p = fmadd(p, z, L(-3.33329491539e-1f));
  const L y = offset + fmadd(p * z, reduced, reduced);
  return select(negative, L(0.0f) - y, y);
}

// The angle of q's turn about its frame's z axis, the twist of a swing-twist split: in
// (-pi, pi], 2 atan2(q.z, q.w).
template <class L>
SOFTSTEP_INLINE L twist_angle_z(const Quat<L>& q_any) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const Quat<L> q = short_way(q_any);
  const auto usable = q.w > L(0.0f);
  const L t = q.z / select(usable, q.w, L(1.0f));
  return select(usable, L(2.0f) * atan_lanes(t), select(q.z < L(0.0f), L(-kPi), L(kPi)));
}

// x wrapped into [-pi, pi] from (-3 pi, 3 pi).
template <class L>
SOFTSTEP_INLINE L wrap_angle(const L& x) {
  constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
  constexpr float kPi = std::numbers::pi_v<float>;
  return select(x > L(kPi), x - L(kTwoPi), select(x < L(-kPi), x + L(kTwoPi), x));
}

// The rotation taking frame a to frame b, as a rotation vector in the world (2 vec(q) of the
// short way: the angle times the axis for small angles, 2 sin(angle/2) times it in general).
// Its rate is w_b - w_a at zero error: the angular locks' C with J = [-1, 1].
template <class L>
SOFTSTEP_INLINE Vec3<L> rotation_error(const Quat<L>& frame_a, const Quat<L>& frame_b) {
  const Quat<L> q = short_way(multiply(frame_b, conjugate(frame_a)));
  return {L(2.0f) * q.x, L(2.0f) * q.y, L(2.0f) * q.z};
}

}  // namespace softstep::simd
