// Rows solved together as one block: the point's 3 rows, an angular lock's 2 or 3, a slider's
// 2 lateral rows. A block removes its velocity error in one step, where rows taken one at a
// time would fight each other (their Jacobians are coupled through the bodies' masses).
// Each returns the change dP of the block's accumulated impulse (see rows.hpp for the modes).
#pragma once

#include "softstep/simd/parts/rows.hpp"

namespace softstep::simd {

template <class L>
struct Vec2 {
  L x, y;
};

template <class L>
SOFTSTEP_INLINE Vec2<L> operator*(const L& s, const Vec2<L>& a) {
  return {s * a.x, s * a.y};
}

// Symmetric 2x2 matrix.
template <class L>
struct Mat2Sym {
  L xx, yy, xy;
};

template <class L>
SOFTSTEP_INLINE Vec2<L> operator*(const Mat2Sym<L>& m, const Vec2<L>& v) {
  return {fmadd(m.xx, v.x, m.xy * v.y), fmadd(m.xy, v.x, m.yy * v.y)};
}

// Inverse of a symmetric positive semi-definite 2x2 matrix, scaled by its largest diagonal
// entry first (as the 3x3 inverse_or_zero, for the same float-range reason); zero where
// singular.
template <class L>
SOFTSTEP_INLINE Mat2Sym<L> inverse_or_zero(const Mat2Sym<L>& k) {
  const L scale = max_lanes(k.xx, k.yy);
  const auto usable = scale > L(0.0f);
  const L inv_scale = select(usable, L(1.0f) / select(usable, scale, L(1.0f)), L(0.0f));
  const L xx = k.xx * inv_scale, yy = k.yy * inv_scale, xy = k.xy * inv_scale;
  const L det = fmadd(xx, yy, L(0.0f) - xy * xy);
  const auto ok = det > L(0.0f);
  const L f = select(ok, inv_scale / select(ok, det, L(1.0f)), L(0.0f));
  return {yy * f, xx * f, (L(0.0f) - xy) * f};
}

// Three rows with velocity error cdot, position error c, K = k (and its inverse), and the
// accumulated impulse: the ball joint's solve, written once for the point and angular locks.
template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE Vec3<L> block3_impulse(const Vec3<L>& cdot, const Vec3<L>& c, const Mat3Sym<L>& k,
                                       const Mat3Sym<L>& k_inv, const Vec3<L>& accumulated,
                                       const RowCoefficients<L>& co) {
  if constexpr (kUseBias) {
    Vec3<L> bias = co.bias_rate * c;  // a spring's bias is never bounded
    if constexpr (kRow != RowKind::Soft) {
      const Vec3<L> fed_back = co.feedback * (k * accumulated);  // gamma' P
      bias = {bounded_bias<L, kRow>(bias.x, fed_back.x, co.max_bias),
              bounded_bias<L, kRow>(bias.y, fed_back.y, co.max_bias),
              bounded_bias<L, kRow>(bias.z, fed_back.z, co.max_bias)};
    }
    const Vec3<L> rigid_dp = k_inv * (cdot + bias);
    const L neg_mass_scale = L(0.0f) - co.mass_scale;
    return {fmadd(neg_mass_scale, rigid_dp.x, L(0.0f) - co.impulse_scale * accumulated.x),
            fmadd(neg_mass_scale, rigid_dp.y, L(0.0f) - co.impulse_scale * accumulated.y),
            fmadd(neg_mass_scale, rigid_dp.z, L(0.0f) - co.impulse_scale * accumulated.z)};
  } else if constexpr (kRow == RowKind::Rigid) {
    return L(-1.0f) * (k_inv * cdot);  // relax_scale is 1: (0 - 1) x, the general kernel's value
  } else {
    return (L(0.0f) - co.relax_scale) * (k_inv * cdot);
  }
}

// The same for two rows (rigid or soft, never per lane: the 2-row blocks are locks). Each
// row's bias is bounded by max_bias times its `bound_scale`: 1 for rows along unit axes (a
// slider's lateral rows), the length of a row whose Jacobian is not a unit vector (the hinge
// lock, angular_parts.hpp), so that the bound stays a bound on the bodies' speed.
template <class L, bool kUseBias>
SOFTSTEP_INLINE Vec2<L> block2_impulse(const Vec2<L>& cdot, const Vec2<L>& c, const Mat2Sym<L>& k,
                                       const Mat2Sym<L>& k_inv, const Vec2<L>& accumulated,
                                       const RowCoefficients<L>& co,
                                       const Vec2<L>& bound_scale = {L(1.0f), L(1.0f)}) {
  if constexpr (kUseBias) {
    const Vec2<L> fed_back = co.feedback * (k * accumulated);
    const Vec2<L> bias{bounded_bias<L, RowKind::Rigid>(co.bias_rate * c.x, fed_back.x,
                                                       co.max_bias * bound_scale.x),
                       bounded_bias<L, RowKind::Rigid>(co.bias_rate * c.y, fed_back.y,
                                                       co.max_bias * bound_scale.y)};
    const Vec2<L> rigid_dp = k_inv * Vec2<L>{cdot.x + bias.x, cdot.y + bias.y};
    const L neg_mass_scale = L(0.0f) - co.mass_scale;
    return {fmadd(neg_mass_scale, rigid_dp.x, L(0.0f) - co.impulse_scale * accumulated.x),
            fmadd(neg_mass_scale, rigid_dp.y, L(0.0f) - co.impulse_scale * accumulated.y)};
  } else {
    const Vec2<L> v = k_inv * cdot;
    return {L(0.0f) - v.x, L(0.0f) - v.y};
  }
}

// The change that keeps a block's accumulated impulse within a ball of radius max_impulse:
// (accumulated + dp) scaled onto the ball when outside it, minus accumulated (a motor joint's
// force and torque caps).
template <class L>
SOFTSTEP_INLINE Vec3<L> capped_change(const Vec3<L>& accumulated, const Vec3<L>& dp,
                                      const L& max_impulse) {
  const Vec3<L> wanted = accumulated + dp;
  const L length = sqrt_lanes(dot(wanted, wanted));
  const auto over = length > max_impulse;
  const L scale = select(over, max_impulse / select(over, length, L(1.0f)), L(1.0f));
  return scale * wanted - accumulated;
}

}  // namespace softstep::simd
