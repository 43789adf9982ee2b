// Ball joint: three rows that keep anchor A and anchor B together,
//   C = (p_B + r_B) - (p_A + r_A),   J v = v_B + w_B x r_B - v_A - w_A x r_A,
// solved as one 3x3 block with K = J M^-1 J^T. One source for every lane width.
#pragma once

#include <cstdint>
#include <limits>

#include "softstep/simd/step_context.hpp"

namespace softstep::simd {

template <int W>
struct alignas(32) BallJointGroup {
  std::int32_t body_a[W];
  std::int32_t body_b[W];
  // Written before prepare each step (core's anchor pass), world frame, step start:
  float r_a[3][W];           // anchor A - centre of mass A, m
  float r_b[3][W];           // anchor B - centre of mass B, m
  float center_delta[3][W];  // centre B - centre A, m (from double positions: precise far out)
  // Spring, constant while the joint lives: hertz +inf = rigid, 0 = free.
  float hertz[W];
  float zeta[W];
  // Prepared once per step:
  float k_inv[6][W];  // effective mass matrix K^-1 = (J M^-1 J^T)^-1: xx yy zz xy xz yz
  float bias_rate[W];
  float mass_scale[W];
  float impulse_scale[W];
  float max_bias[W];     // m/s, +inf for soft rows
  float relax_scale[W];  // 1 for rigid rows, 0 for springs (springs are not relaxed)
  // Accumulated impulse of the current sub-step, N s, world frame: the warm start.
  float impulse[3][W];
};

namespace detail {
template <class L>
inline Vec3<L> load3(const float (&a)[3][kWidth<L>]) {
  return {load<L>(a[0]), load<L>(a[1]), load<L>(a[2])};
}
template <class L>
inline void store3(float (&a)[3][kWidth<L>], const Vec3<L>& v) {
  store_lanes(a[0], v.x);
  store_lanes(a[1], v.y);
  store_lanes(a[2], v.z);
}
template <class L>
inline void apply_impulse(BodyLanes<L>& a, BodyLanes<L>& b, const Vec3<L>& r_a, const Vec3<L>& r_b,
                          const Vec3<L>& p) {
  a.v = mul_add(L(0.0f) - a.inv_mass, p, a.v);
  a.w = a.w - a.inv_inertia * cross(r_a, p);
  b.v = mul_add(b.inv_mass, p, b.v);
  b.w = b.w + b.inv_inertia * cross(r_b, p);
}
template <class L>
inline Vec3<L> relative_velocity(const BodyLanes<L>& a, const BodyLanes<L>& b, const Vec3<L>& r_a,
                                 const Vec3<L>& r_b) {
  return (b.v + cross(b.w, r_b)) - (a.v + cross(a.w, r_a));
}
template <class L>
inline Vec3<L> clamp3(const Vec3<L>& v, const L& bound) {
  const L lo = L(0.0f) - bound;
  return {min_lanes(max_lanes(v.x, lo), bound), min_lanes(max_lanes(v.y, lo), bound),
          min_lanes(max_lanes(v.z, lo), bound)};
}
}  // namespace detail

// Effective mass and softness for the step. Reads r_a, r_b, hertz, zeta and body masses.
template <class L>
inline void prepare_ball_joints(BallJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                const SubstepContext& ctx) {
  const MassLanes<L> ma = gather_mass<L>(bodies.mass, g.body_a);
  const MassLanes<L> mb = gather_mass<L>(bodies.mass, g.body_b);
  const L m_sum = ma.inv_mass + mb.inv_mass;
  const Mat3Sym<L> k = Mat3Sym<L>{m_sum, m_sum, m_sum, L(0.0f), L(0.0f), L(0.0f)} +
                       rotational_mass_term(ma.inv_inertia, detail::load3<L>(g.r_a)) +
                       rotational_mass_term(mb.inv_inertia, detail::load3<L>(g.r_b));
  const Mat3Sym<L> k_inv = inverse_or_zero(k);
  store_lanes(g.k_inv[0], k_inv.xx);
  store_lanes(g.k_inv[1], k_inv.yy);
  store_lanes(g.k_inv[2], k_inv.zz);
  store_lanes(g.k_inv[3], k_inv.xy);
  store_lanes(g.k_inv[4], k_inv.xz);
  store_lanes(g.k_inv[5], k_inv.yz);

  const L hertz = load<L>(g.hertz);
  const auto rigid = hertz == L(kRigidHertz);
  const Softness<L> spring = make_softness(select(rigid, L(0.0f), hertz), load<L>(g.zeta), ctx.h);
  store_lanes(g.bias_rate, select(rigid, L(ctx.rigid.bias_rate), spring.bias_rate));
  store_lanes(g.mass_scale, select(rigid, L(ctx.rigid.mass_scale), spring.mass_scale));
  store_lanes(g.impulse_scale, select(rigid, L(ctx.rigid.impulse_scale), spring.impulse_scale));
  store_lanes(g.max_bias,
              select(rigid, L(ctx.max_correction_speed), L(std::numeric_limits<float>::infinity())));
  store_lanes(g.relax_scale, select(rigid, L(1.0f), L(0.0f)));
}

template <class L>
inline void warm_start_ball_joints(BallJointGroup<kWidth<L>>& g, const BodyArrays& bodies) {
  BodyLanes<L> a = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  BodyLanes<L> b = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  const Vec3<L> r_a = rotate(a.dq, detail::load3<L>(g.r_a));
  const Vec3<L> r_b = rotate(b.dq, detail::load3<L>(g.r_b));
  detail::apply_impulse(a, b, r_a, r_b, detail::load3<L>(g.impulse));
  scatter_velocity(bodies.velocity, g.body_a, a);
  scatter_velocity(bodies.velocity, g.body_b, b);
}

// kUseBias = true: the soft, biased solve. false: the rigid relax pass (no bias, springs
// untouched: a spring's one soft solve per sub-step is exactly implicit Euler, talk 2:3:2).
template <class L, bool kUseBias>
inline void solve_ball_joints(BallJointGroup<kWidth<L>>& g, const BodyArrays& bodies) {
  BodyLanes<L> a = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  BodyLanes<L> b = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  const Vec3<L> r_a = rotate(a.dq, detail::load3<L>(g.r_a));
  const Vec3<L> r_b = rotate(b.dq, detail::load3<L>(g.r_b));
  const Mat3Sym<L> k_inv{load<L>(g.k_inv[0]), load<L>(g.k_inv[1]), load<L>(g.k_inv[2]),
                         load<L>(g.k_inv[3]), load<L>(g.k_inv[4]), load<L>(g.k_inv[5])};
  const Vec3<L> cdot = detail::relative_velocity(a, b, r_a, r_b);
  Vec3<L> accumulated = detail::load3<L>(g.impulse);
  Vec3<L> dp;
  if constexpr (kUseBias) {
    const Vec3<L> c = detail::load3<L>(g.center_delta) + (b.dp - a.dp) + (r_b - r_a);
    const Vec3<L> bias = detail::clamp3(load<L>(g.bias_rate) * c, load<L>(g.max_bias));
    const Vec3<L> rigid_dp = k_inv * (cdot + bias);
    const L mass_scale = load<L>(g.mass_scale);
    const L impulse_scale = load<L>(g.impulse_scale);
    dp = {fmadd(L(0.0f) - mass_scale, rigid_dp.x, L(0.0f) - impulse_scale * accumulated.x),
          fmadd(L(0.0f) - mass_scale, rigid_dp.y, L(0.0f) - impulse_scale * accumulated.y),
          fmadd(L(0.0f) - mass_scale, rigid_dp.z, L(0.0f) - impulse_scale * accumulated.z)};
  } else {
    dp = (L(0.0f) - load<L>(g.relax_scale)) * (k_inv * cdot);
  }
  detail::store3<L>(g.impulse, accumulated + dp);
  detail::apply_impulse(a, b, r_a, r_b, dp);
  scatter_velocity(bodies.velocity, g.body_a, a);
  scatter_velocity(bodies.velocity, g.body_b, b);
}

}  // namespace softstep::simd
