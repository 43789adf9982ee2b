// Axis part: one linear row along a unit world axis n between a point of A and a point of B.
//   J v = n . (v_B - v_A) + (arm_B x n) . w_B - (arm_A x n) . w_A
//   K   = m_A^-1 + m_B^-1 + (arm_A x n) . I_A^-1 (arm_A x n) + (arm_B x n) . I_B^-1 (arm_B x n)
// The arms are where the impulse acts: the anchors for a distance joint (its n follows the
// anchors, so the rotation of n adds nothing), and for a slider, whose n turns with A, A's arm
// reaches to B's anchor (r_A + d, d = anchor B - anchor A), which adds (n x d) . w_A to J v.
// Modes: rigid, soft, free, limit, motor (rows.hpp). Used by the distance joint (spring and
// limits) and the prismatic joint (its axis's limit, motor and spring).
#pragma once

#include "softstep/simd/parts/rows.hpp"

namespace softstep::simd {

// K = J M^-1 J^T along the unit axis n, with the impulse at arm_a and arm_b.
template <class L>
SOFTSTEP_INLINE L axial_constraint_mass(const L& inv_mass_a, const Mat3Sym<L>& inv_inertia_a,
                                        const Vec3<L>& arm_a, const L& inv_mass_b,
                                        const Mat3Sym<L>& inv_inertia_b, const Vec3<L>& arm_b,
                                        const Vec3<L>& n) {
  const Vec3<L> ran = cross(arm_a, n);
  const Vec3<L> rbn = cross(arm_b, n);
  return inv_mass_a + inv_mass_b + dot(ran, inv_inertia_a * ran) + dot(rbn, inv_inertia_b * rbn);
}

// 1 / (J M^-1 J^T) along the unit axis n.
template <class L>
SOFTSTEP_INLINE L axial_mass(const L& inv_mass_a, const Mat3Sym<L>& inv_inertia_a,
                             const Vec3<L>& arm_a, const L& inv_mass_b,
                             const Mat3Sym<L>& inv_inertia_b, const Vec3<L>& arm_b,
                             const Vec3<L>& n) {
  return inverse_or_zero(
      axial_constraint_mass(inv_mass_a, inv_inertia_a, arm_a, inv_mass_b, inv_inertia_b, arm_b, n));
}

inline constexpr float kMinAxisLength = 1.0e-6f;  // m: below it a distance's axis is undefined

// d / |d| and |d|; zero where |d| is below kMinAxisLength.
template <class L>
SOFTSTEP_INLINE Vec3<L> normalize_or_zero(const Vec3<L>& d, L& length) {
  length = sqrt_lanes(dot(d, d));
  const auto ok = length > L(kMinAxisLength);
  const L inv = select(ok, L(1.0f) / select(ok, length, L(1.0f)), L(0.0f));
  return inv * d;
}

// A row along A's axis n between the anchors (a slider's): its arms, K and m_eff.
template <class L>
struct SliderAxis {
  Vec3<L> n;
  Vec3<L> arm_a;  // r_A + d: the impulse on A acts at B's anchor
  L k, m_eff;
};

template <class L>
SOFTSTEP_INLINE SliderAxis<L> slider_axis(const JointBodies<L>& j, const Vec3<L>& n) {
  SliderAxis<L> s{n, j.r_a + j.separation, L(0.0f), L(0.0f)};
  s.k = axial_constraint_mass(j.a.inv_mass, j.a.inv_inertia, s.arm_a, j.b.inv_mass, j.b.inv_inertia,
                              j.r_b, n);
  s.m_eff = inverse_or_zero(s.k);
  return s;
}

// J v of a slider row (see the top of this file).
template <class L>
SOFTSTEP_INLINE L slider_velocity(const JointBodies<L>& j, const SliderAxis<L>& s) {
  return dot(s.n, j.b.v - j.a.v) + dot(j.b.w, cross(j.r_b, s.n)) - dot(j.a.w, cross(s.arm_a, s.n));
}

template <class L>
SOFTSTEP_INLINE void apply_slider_impulse(JointBodies<L>& j, const SliderAxis<L>& s,
                                          const L& impulse) {
  apply_impulse_at(j, impulse * s.n, s.arm_a, j.r_b);
}

// A slider row as solve_axis_controls (frame_lanes.hpp) wants it: the velocity, K and m_eff,
// and an apply that refreshes the velocity.
template <class L>
struct SlideAxis {
  JointBodies<L>& j;
  SliderAxis<L> row;
  L k, m_eff;
  L velocity;
  L cdot() const { return velocity; }
  void apply(const L& impulse) {
    apply_slider_impulse(j, row, impulse);
    velocity = slider_velocity(j, row);
  }
};

}  // namespace softstep::simd
