// Point part: three linear rows that keep anchor A and anchor B together,
//   C = (p_B + r_B) - (p_A + r_A),   J v = v_B + w_B x r_B - v_A - w_A x r_A,
//   K = J M^-1 J^T = (m_A^-1 + m_B^-1) 1 + S(r_A)^T I_A^-1 S(r_A) + S(r_B)^T I_B^-1 S(r_B),
// solved as one 3x3 block. Rigid, soft or free (the caller does not call). Used by the
// ball, revolute and weld joints.
//
// K is rebuilt from the current anchors in every solve, not kept from the step start:
// with anchors off the centre of mass K is strongly anisotropic (for the chain's spheres
// r^2/I is 4x 1/m), and once a link turns ~30 degrees within a step a stale K over-corrects
// and Gauss-Seidel diverges. A 1,000-link chain did, at 4 sub-steps; it is stable since.
#pragma once

#include "softstep/simd/parts/blocks.hpp"

namespace softstep::simd {

template <class L>
SOFTSTEP_INLINE Mat3Sym<L> point_constraint_mass(const L& inv_mass_a,
                                                 const Mat3Sym<L>& inv_inertia_a,
                                                 const Vec3<L>& r_a, const L& inv_mass_b,
                                                 const Mat3Sym<L>& inv_inertia_b,
                                                 const Vec3<L>& r_b) {
  const L m_sum = inv_mass_a + inv_mass_b;
  return Mat3Sym<L>{m_sum, m_sum, m_sum, L(0.0f), L(0.0f), L(0.0f)} +
         rotational_mass_term(inv_inertia_a, r_a) + rotational_mass_term(inv_inertia_b, r_b);
}

// The effective mass matrix K^-1 (zero where K is singular).
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> inverse_effective_mass(const L& inv_mass_a,
                                                  const Mat3Sym<L>& inv_inertia_a,
                                                  const Vec3<L>& r_a, const L& inv_mass_b,
                                                  const Mat3Sym<L>& inv_inertia_b,
                                                  const Vec3<L>& r_b) {
  return inverse_or_zero(
      point_constraint_mass(inv_mass_a, inv_inertia_a, r_a, inv_mass_b, inv_inertia_b, r_b));
}

// One pass of the point's rows over W joints; `impulse` is the part's accumulated impulse
// (N s, world frame, on B).
template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE void solve_point(JointBodies<L>& j, float (&impulse)[3][kWidth<L>],
                                 const RowCoefficients<L>& co) {
  const Mat3Sym<L> k = point_constraint_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                                             j.b.inv_inertia, j.r_b);
  const Mat3Sym<L> k_inv = inverse_or_zero(k);
  const Vec3<L> accumulated = load3<L>(impulse);
  const Vec3<L> dp = block3_impulse<L, kUseBias, kRow>(relative_velocity(j), j.separation, k, k_inv,
                                                       accumulated, co);
  store3<L>(impulse, accumulated + dp);
  apply_impulse(j, dp);
}

template <class L>
SOFTSTEP_INLINE void warm_start_point(JointBodies<L>& j, const float (&impulse)[3][kWidth<L>]) {
  apply_impulse(j, load3<L>(impulse));
}

}  // namespace softstep::simd
