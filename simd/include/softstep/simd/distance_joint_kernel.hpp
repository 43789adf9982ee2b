// Distance joint: one axis n = d/|d| between the anchors, d = (p_B + r_B) - (p_A + r_A).
//   spring row:   C = |d| - rest_length      (rigid rod, soft spring, or absent when free)
//   lower limit:  C = |d| - min_length >= 0  (impulse >= 0)
//   upper limit:  C = max_length - |d| >= 0  (impulse >= 0): with a free spring, a rope
// The rows share the axial mass 1/(J M^-1 J^T), taken at the step start.
#pragma once

#include <cstdint>
#include <limits>

#include "softstep/simd/ball_joint_kernel.hpp"

namespace softstep::simd {

template <int W>
struct alignas(32) DistanceJointGroup {
  std::int32_t body_a[W];
  std::int32_t body_b[W];
  float r_a[3][W];
  float r_b[3][W];
  float center_delta[3][W];
  float hertz[W];  // +inf rigid rod, 0 no spring
  float zeta[W];
  float rest_length[W];  // already clamped into [min_length, max_length]
  float min_length[W];
  float max_length[W];
  float lower_enabled[W];  // 1 when the lower limit row exists (min > 0, not rigid), else 0
  float upper_enabled[W];  // 1 when the upper limit row exists (max finite, not rigid), else 0
  // Prepared once per step:
  float axial_mass[W];
  float bias_rate[W];
  float mass_scale[W];
  float impulse_scale[W];
  float max_bias[W];
  float relax_scale[W];
  // Accumulated impulses of the current sub-step along n, N s:
  float impulse[W];
  float lower_impulse[W];
  float upper_impulse[W];
};

namespace detail {
inline constexpr float kMinAxisLength = 1.0e-6f;  // m: below it the axis is undefined

template <class L>
inline Vec3<L> normalize_or_zero(const Vec3<L>& d, L& length) {
  length = sqrt_lanes(dot(d, d));
  const auto ok = length > L(kMinAxisLength);
  const L inv = select(ok, L(1.0f) / select(ok, length, L(1.0f)), L(0.0f));
  return inv * d;
}

template <class L>
inline L axial_velocity(const BodyLanes<L>& a, const BodyLanes<L>& b, const Vec3<L>& r_a,
                        const Vec3<L>& r_b, const Vec3<L>& n) {
  return dot(n, relative_velocity(a, b, r_a, r_b));
}

// One unilateral limit row (C >= 0 wanted, impulse >= 0). Ahead of contact (C > 0) the row
// is speculative: it lets the gap close in one sub-step but not further, in solve and relax.
template <class L, bool kUseBias>
inline L limit_impulse(const L& c, const L& cdot, const L& axial_mass, const L& accumulated,
                       const SubstepContext& ctx) {
  const auto ahead = c > L(0.0f);
  L bias = select(ahead, c * L(ctx.inv_h), L(0.0f));
  L mass_scale(1.0f);
  L impulse_scale(0.0f);
  if constexpr (kUseBias) {
    const L rigid_bias = max_lanes(L(ctx.rigid.bias_rate) * c, L(0.0f) - L(ctx.max_correction_speed));
    bias = select(ahead, bias, rigid_bias);
    mass_scale = select(ahead, mass_scale, L(ctx.rigid.mass_scale));
    impulse_scale = select(ahead, impulse_scale, L(ctx.rigid.impulse_scale));
  }
  const L raw = fmadd(L(0.0f) - mass_scale * axial_mass, cdot + bias, L(0.0f) - impulse_scale * accumulated);
  return max_lanes(accumulated + raw, L(0.0f));  // the new accumulated impulse
}
}  // namespace detail

template <class L>
inline void prepare_distance_joints(DistanceJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                    const SubstepContext& ctx) {
  const MassLanes<L> a = gather_mass<L>(bodies.mass, g.body_a);
  const MassLanes<L> b = gather_mass<L>(bodies.mass, g.body_b);
  const Vec3<L> r_a = detail::load3<L>(g.r_a);
  const Vec3<L> r_b = detail::load3<L>(g.r_b);
  L length;
  const Vec3<L> n = detail::normalize_or_zero(detail::load3<L>(g.center_delta) + (r_b - r_a), length);
  const Vec3<L> ran = cross(r_a, n);
  const Vec3<L> rbn = cross(r_b, n);
  const L k = a.inv_mass + b.inv_mass + dot(ran, a.inv_inertia * ran) + dot(rbn, b.inv_inertia * rbn);
  const auto ok = k > L(0.0f);
  store_lanes(g.axial_mass, select(ok, L(1.0f) / select(ok, k, L(1.0f)), L(0.0f)));

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
inline void warm_start_distance_joints(DistanceJointGroup<kWidth<L>>& g, const BodyArrays& bodies) {
  BodyLanes<L> a = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  BodyLanes<L> b = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  const Vec3<L> r_a = rotate(a.dq, detail::load3<L>(g.r_a));
  const Vec3<L> r_b = rotate(b.dq, detail::load3<L>(g.r_b));
  L length;
  const Vec3<L> d = detail::load3<L>(g.center_delta) + (b.dp - a.dp) + (r_b - r_a);
  const Vec3<L> n = detail::normalize_or_zero(d, length);
  const L total = load<L>(g.impulse) + load<L>(g.lower_impulse) - load<L>(g.upper_impulse);
  detail::apply_impulse(a, b, r_a, r_b, total * n);
  scatter_velocity(bodies.velocity, g.body_a, a);
  scatter_velocity(bodies.velocity, g.body_b, b);
}

template <class L, bool kUseBias>
inline void solve_distance_joints(DistanceJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                  const SubstepContext& ctx) {
  BodyLanes<L> a = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  BodyLanes<L> b = gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  const Vec3<L> r_a = rotate(a.dq, detail::load3<L>(g.r_a));
  const Vec3<L> r_b = rotate(b.dq, detail::load3<L>(g.r_b));
  L length;
  const Vec3<L> d = detail::load3<L>(g.center_delta) + (b.dp - a.dp) + (r_b - r_a);
  const Vec3<L> n = detail::normalize_or_zero(d, length);
  const L axial_mass = load<L>(g.axial_mass);

  // Spring or rod row.
  {
    const L cdot = detail::axial_velocity(a, b, r_a, r_b, n);
    const L accumulated = load<L>(g.impulse);
    L dp;
    if constexpr (kUseBias) {
      const L c = length - load<L>(g.rest_length);
      const L bound = load<L>(g.max_bias);
      const L bias = min_lanes(max_lanes(load<L>(g.bias_rate) * c, L(0.0f) - bound), bound);
      dp = fmadd(L(0.0f) - load<L>(g.mass_scale) * axial_mass, cdot + bias,
                 L(0.0f) - load<L>(g.impulse_scale) * accumulated);
    } else {
      dp = (L(0.0f) - load<L>(g.relax_scale)) * axial_mass * cdot;
    }
    store_lanes(g.impulse, accumulated + dp);
    detail::apply_impulse(a, b, r_a, r_b, dp * n);
  }
  // Lower limit: pushes apart.
  {
    const auto enabled = load<L>(g.lower_enabled) > L(0.0f);
    const L cdot = detail::axial_velocity(a, b, r_a, r_b, n);
    const L accumulated = load<L>(g.lower_impulse);
    const L next = detail::limit_impulse<L, kUseBias>(length - load<L>(g.min_length), cdot,
                                                      axial_mass, accumulated, ctx);
    const L dp = select(enabled, next - accumulated, L(0.0f));
    store_lanes(g.lower_impulse, accumulated + dp);
    detail::apply_impulse(a, b, r_a, r_b, dp * n);
  }
  // Upper limit: pulls together (acts along -n).
  {
    const auto enabled = load<L>(g.upper_enabled) > L(0.0f);
    const L cdot = L(0.0f) - detail::axial_velocity(a, b, r_a, r_b, n);
    const L accumulated = load<L>(g.upper_impulse);
    const L next = detail::limit_impulse<L, kUseBias>(load<L>(g.max_length) - length, cdot,
                                                      axial_mass, accumulated, ctx);
    const L dp = select(enabled, next - accumulated, L(0.0f));
    store_lanes(g.upper_impulse, accumulated + dp);
    detail::apply_impulse(a, b, r_a, r_b, (L(0.0f) - dp) * n);
  }
  scatter_velocity(bodies.velocity, g.body_a, a);
  scatter_velocity(bodies.velocity, g.body_b, b);
}

}  // namespace softstep::simd
