// Distance joint: one axis n = d/|d| between the anchors, d = (p_B + r_B) - (p_A + r_A).
//   spring row:   C = |d| - rest_length      (rigid rod, soft spring, or absent when free)
//   lower limit:  C = |d| - min_length >= 0  (impulse >= 0)
//   upper limit:  C = max_length - |d| >= 0  (impulse >= 0): with a free spring, a rope
// The rows share the axial mass 1/(J M^-1 J^T), from the current anchors and axis in every
// solve (see ball_joint_kernel.hpp for why a step-start mass is not good enough).
#pragma once

#include "softstep/simd/joint_lanes.hpp"

namespace softstep::simd {

template <int W>
struct alignas(32) DistanceJointGroup : JointLanes<W> {
  float rest_length[W];  // already clamped into [min_length, max_length]
  float min_length[W];
  float max_length[W];
  float lower_enabled[W];  // 1 when the lower limit row exists (min > 0, not rigid), else 0
  float upper_enabled[W];  // 1 when the upper limit row exists (max finite, not rigid), else 0
  // Accumulated impulses of the current sub-step along n, N s:
  float impulse[W];
  float lower_impulse[W];
  float upper_impulse[W];
};

// K = J M^-1 J^T along the unit axis n.
template <class L>
SOFTSTEP_INLINE L axial_constraint_mass(const L& inv_mass_a, const Mat3Sym<L>& inv_inertia_a,
                                        const Vec3<L>& r_a, const L& inv_mass_b,
                                        const Mat3Sym<L>& inv_inertia_b, const Vec3<L>& r_b,
                                        const Vec3<L>& n) {
  const Vec3<L> ran = cross(r_a, n);
  const Vec3<L> rbn = cross(r_b, n);
  return inv_mass_a + inv_mass_b + dot(ran, inv_inertia_a * ran) + dot(rbn, inv_inertia_b * rbn);
}

// 1/k, or 0 where k is not positive (neither body can move along the axis).
template <class L>
SOFTSTEP_INLINE L inverse_or_zero(const L& k) {
  const auto ok = k > L(0.0f);
  return select(ok, L(1.0f) / select(ok, k, L(1.0f)), L(0.0f));
}

// 1 / (J M^-1 J^T) along the unit axis n.
template <class L>
SOFTSTEP_INLINE L axial_mass(const L& inv_mass_a, const Mat3Sym<L>& inv_inertia_a,
                             const Vec3<L>& r_a, const L& inv_mass_b,
                             const Mat3Sym<L>& inv_inertia_b, const Vec3<L>& r_b,
                             const Vec3<L>& n) {
  return inverse_or_zero(
      axial_constraint_mass(inv_mass_a, inv_inertia_a, r_a, inv_mass_b, inv_inertia_b, r_b, n));
}

namespace detail {
inline constexpr float kMinAxisLength = 1.0e-6f;  // m: below it the axis is undefined

template <class L>
SOFTSTEP_INLINE Vec3<L> normalize_or_zero(const Vec3<L>& d, L& length) {
  length = sqrt_lanes(dot(d, d));
  const auto ok = length > L(kMinAxisLength);
  const L inv = select(ok, L(1.0f) / select(ok, length, L(1.0f)), L(0.0f));
  return inv * d;
}

// One unilateral limit row acting along sign * n (C >= 0 wanted, impulse >= 0). Ahead of
// contact (C > 0) it is speculative: the gap may close within one sub-step but not beyond,
// in solve and relax alike.
template <class L, bool kUseBias, bool kPerLaneEnable>
SOFTSTEP_INLINE void solve_limit_row(JointBodies<L>& j, const Vec3<L>& n, const L& sign, const L& c,
                                     const L& k, const L& axial, const float* enabled,
                                     float* accumulated_lanes, const SubstepContext& ctx) {
  const L cdot = sign * dot(n, relative_velocity(j));
  const L accumulated = load<L>(accumulated_lanes);
  const auto ahead = c > L(0.0f);
  L bias = select(ahead, c * L(ctx.inv_h), L(0.0f));
  L mass_scale(1.0f);
  L impulse_scale(0.0f);
  if constexpr (kUseBias) {
    // Only the pushing direction is bounded: bias_rate C + gamma' P >= -max_correction_speed
    // (see bounded_bias for why the sum and not the bias alone).
    const L fed_back = L(ctx.rigid.feedback) * k * accumulated;
    const L rigid_bias =
        max_lanes(L(ctx.rigid.bias_rate) * c + fed_back, L(0.0f) - L(ctx.max_correction_speed)) -
        fed_back;
    bias = select(ahead, bias, rigid_bias);
    mass_scale = select(ahead, mass_scale, L(ctx.rigid.mass_scale));
    impulse_scale = select(ahead, impulse_scale, L(ctx.rigid.impulse_scale));
  }
  const L raw =
      fmadd(L(0.0f) - mass_scale * axial, cdot + bias, L(0.0f) - impulse_scale * accumulated);
  const L next = max_lanes(accumulated + raw, L(0.0f));
  L dp = next - accumulated;
  if constexpr (kPerLaneEnable) dp = select(load<L>(enabled) > L(0.0f), dp, L(0.0f));
  store_lanes(accumulated_lanes, accumulated + dp);
  apply_impulse(j, (sign * dp) * n);
}
}  // namespace detail

// Which passes a distance-joint variant needs: the spring row unless it is free, the limit
// rows it has; relax only for a rod or a limit (springs are not relaxed).
inline constexpr bool distance_needs_solve(JointFeatures f) {
  return f.row != RowKind::Free || f.lower || f.upper;
}
inline constexpr bool distance_needs_relax(JointFeatures f) {
  return f.row == RowKind::Any || f.row == RowKind::Rigid || f.lower || f.upper;
}

template <class L, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void prepare_distance_joints(DistanceJointGroup<kWidth<L>>& g,
                                             const SubstepContext& ctx) {
  prepare_row_coefficients<L, F>(g, ctx);
}

template <class L, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void warm_start_distance_joints(DistanceJointGroup<kWidth<L>>& g,
                                                const BodyArrays& bodies) {
  if constexpr (!distance_needs_solve(F)) return;
  JointBodies<L> j = gather_joint<L>(g, bodies);
  L length;
  const Vec3<L> n = detail::normalize_or_zero(j.separation, length);
  // Rows a variant lacks hold 0; the general kernel adds their zeros.
  L total = F.row == RowKind::Free ? L(0.0f) : load<L>(g.impulse);
  if constexpr (F.lower) total = total + load<L>(g.lower_impulse);
  if constexpr (F.upper) total = total - load<L>(g.upper_impulse);
  apply_impulse(j, total * n);
  scatter_joint(g, bodies, j);
}

template <class L, bool kUseBias, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void solve_distance_joints(DistanceJointGroup<kWidth<L>>& g,
                                           const BodyArrays& bodies, const SubstepContext& ctx) {
  if constexpr (kUseBias ? !distance_needs_solve(F) : !distance_needs_relax(F)) return;
  constexpr bool kAny = F.row == RowKind::Any;
  JointBodies<L> j = gather_joint<L>(g, bodies);
  L length;
  const Vec3<L> n = detail::normalize_or_zero(j.separation, length);
  const L k = axial_constraint_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                                    j.b.inv_inertia, j.r_b, n);
  const L axial = inverse_or_zero(k);

  // Spring or rod row: solved unless free, relaxed only when rigid.
  if constexpr (kUseBias ? F.row != RowKind::Free
                         : (F.row == RowKind::Any || F.row == RowKind::Rigid)) {
    const L cdot = dot(n, relative_velocity(j));
    const L accumulated = load<L>(g.impulse);
    L dp;
    if constexpr (kUseBias) {
      L bias = load<L>(g.bias_rate) * (length - load<L>(g.rest_length));
      if constexpr (F.row != RowKind::Soft) {
        bias = bounded_bias<L, F.row>(bias, load<L>(g.feedback) * k * accumulated,
                                      load<L>(g.max_bias));
      }
      dp = fmadd(L(0.0f) - load<L>(g.mass_scale) * axial, cdot + bias,
                 L(0.0f) - load<L>(g.impulse_scale) * accumulated);
    } else if constexpr (F.row == RowKind::Rigid) {
      dp = L(-1.0f) * axial * cdot;  // relax_scale is 1: (0 - 1) axial cdot, as in general
    } else {
      dp = (L(0.0f) - load<L>(g.relax_scale)) * axial * cdot;
    }
    store_lanes(g.impulse, accumulated + dp);
    apply_impulse(j, dp * n);
  }
  // Lower limit pushes apart (along n), upper limit pulls together (along -n).
  if constexpr (F.lower) {
    detail::solve_limit_row<L, kUseBias, kAny>(j, n, L(1.0f), length - load<L>(g.min_length), k,
                                               axial, g.lower_enabled, g.lower_impulse, ctx);
  }
  if constexpr (F.upper) {
    detail::solve_limit_row<L, kUseBias, kAny>(j, n, L(-1.0f), load<L>(g.max_length) - length, k,
                                               axial, g.upper_enabled, g.upper_impulse, ctx);
  }
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
