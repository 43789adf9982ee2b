// Ball joint: three rows that keep anchor A and anchor B together,
//   C = (p_B + r_B) - (p_A + r_A),   J v = v_B + w_B x r_B - v_A - w_A x r_A,
// solved as one 3x3 block with K = J M^-1 J^T. One source for every lane width.
//
// K is rebuilt from the current anchors in every solve, not kept from the step start:
// with anchors off the centre of mass K is strongly anisotropic (for the chain's spheres
// r^2/I is 4x 1/m), and once a link turns ~30 degrees within a step a stale K over-corrects
// and Gauss-Seidel diverges. A 1,000-link chain did, at 4 sub-steps; it is stable since.
#pragma once

#include "softstep/simd/joint_lanes.hpp"

namespace softstep::simd {

template <int W>
struct alignas(32) BallJointGroup : JointLanes<W> {
  // Accumulated impulse of the current sub-step, N s, world frame: the warm start.
  float impulse[3][W];
};

// K = J M^-1 J^T = (m_A^-1 + m_B^-1) 1 + S(r_A)^T I_A^-1 S(r_A) + S(r_B)^T I_B^-1 S(r_B).
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

// Which passes a ball-joint variant needs at all: a free spring applies nothing (its
// accumulated impulse starts and stays 0), and springs are not relaxed. The plan leaves a
// pass out for a group that does not need it.
inline constexpr bool ball_needs_solve(JointFeatures f) {
  return f.row != RowKind::Free;
}
inline constexpr bool ball_needs_relax(JointFeatures f) {
  return f.row == RowKind::Any || f.row == RowKind::Rigid;
}

template <class L, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void prepare_ball_joints(BallJointGroup<kWidth<L>>& g, const SubstepContext& ctx) {
  prepare_row_coefficients<L, F>(g, ctx);
}

template <class L, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void warm_start_ball_joints(BallJointGroup<kWidth<L>>& g,
                                            const BodyArrays& bodies) {
  if constexpr (ball_needs_solve(F)) {
    JointBodies<L> j = gather_joint<L>(g, bodies);
    apply_impulse(j, load3<L>(g.impulse));
    scatter_joint(g, bodies, j);
  }
}

// kUseBias = true: the soft, biased solve. false: the rigid relax pass (no bias, springs
// untouched: a spring's one soft solve per sub-step is exactly implicit Euler, talk 2:3:2).
template <class L, bool kUseBias, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void solve_ball_joints(BallJointGroup<kWidth<L>>& g, const BodyArrays& bodies) {
  if constexpr (kUseBias ? !ball_needs_solve(F) : !ball_needs_relax(F)) return;
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const Mat3Sym<L> k = point_constraint_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                                             j.b.inv_inertia, j.r_b);
  const Mat3Sym<L> k_inv = inverse_or_zero(k);
  const Vec3<L> cdot = relative_velocity(j);
  const Vec3<L> accumulated = load3<L>(g.impulse);
  Vec3<L> dp;
  if constexpr (kUseBias) {
    const L bias_rate = load<L>(g.bias_rate);
    Vec3<L> bias = bias_rate * j.separation;  // a spring's bias is never bounded
    if constexpr (F.row != RowKind::Soft) {
      const L bound = load<L>(g.max_bias);
      const Vec3<L> fed_back = load<L>(g.feedback) * (k * accumulated);  // gamma' P
      bias = {bounded_bias<L, F.row>(bias.x, fed_back.x, bound),
              bounded_bias<L, F.row>(bias.y, fed_back.y, bound),
              bounded_bias<L, F.row>(bias.z, fed_back.z, bound)};
    }
    const Vec3<L> rigid_dp = k_inv * (cdot + bias);
    const L neg_mass_scale = L(0.0f) - load<L>(g.mass_scale);
    const L impulse_scale = load<L>(g.impulse_scale);
    dp = {fmadd(neg_mass_scale, rigid_dp.x, L(0.0f) - impulse_scale * accumulated.x),
          fmadd(neg_mass_scale, rigid_dp.y, L(0.0f) - impulse_scale * accumulated.y),
          fmadd(neg_mass_scale, rigid_dp.z, L(0.0f) - impulse_scale * accumulated.z)};
  } else if constexpr (F.row == RowKind::Rigid) {
    dp = L(-1.0f) * (k_inv * cdot);  // relax_scale is 1: (0 - 1) x, the general kernel's value
  } else {
    dp = (L(0.0f) - load<L>(g.relax_scale)) * (k_inv * cdot);
  }
  store3<L>(g.impulse, accumulated + dp);
  apply_impulse(j, dp);
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
