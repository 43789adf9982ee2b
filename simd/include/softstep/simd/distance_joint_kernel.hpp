// Distance joint: axis parts (parts/axis_part.hpp) along n = d/|d| between the anchors,
// d = (p_B + r_B) - (p_A + r_A):
//   spring row:   C = |d| - rest_length      (rigid rod, soft spring, or absent when free)
//   lower limit:  C = |d| - min_length >= 0  (impulse >= 0)
//   upper limit:  C = max_length - |d| >= 0  (impulse >= 0): with a free spring, a rope
// The rows share the axial mass 1/(J M^-1 J^T), from the current anchors and axis in every
// solve (see ball_joint_kernel.hpp for why a step-start mass is not good enough).
#pragma once

#include "softstep/simd/parts/axis_part.hpp"

namespace softstep::simd {

template <int W>
struct alignas(kLaneAlign<W>) DistanceJointGroup : JointLanes<W> {
  float rest_length[W];  // already clamped into [min_length, max_length]
  float min_length[W];
  float max_length[W];
  float lower_enabled[W];  // 1 when the lower limit row exists (min > 0, not rigid), else 0
  float upper_enabled[W];  // 1 when the upper limit row exists (max finite, not rigid), else 0
  // A spring in absolute units (Spring::absolute, hertz 0): k in N/m, c in N s/m, converted
  // with the row's K in each solve (with_absolute_spring); both 0 in a relative lane.
  float spring_stiffness[W];
  float spring_damping[W];
  // Accumulated impulses of the current sub-step along n, N s:
  float impulse[W];
  float lower_impulse[W];
  float upper_impulse[W];
};

namespace detail {
// One limit row along sign * n (limit_row_impulse), with a per-lane enable in the general
// kernel.
template <class L, bool kUseBias, bool kPerLaneEnable>
SOFTSTEP_INLINE void solve_limit_row(JointBodies<L>& j, const Vec3<L>& n, const L& sign, const L& c,
                                     const L& k, const L& axial, const float* enabled,
                                     float* accumulated_lanes, const SubstepContext& ctx) {
  const L cdot = sign * dot(n, relative_velocity(j));
  const L accumulated = load<L>(accumulated_lanes);
  L dp = limit_row_impulse<L, kUseBias>(cdot, c, k, axial, accumulated, ctx, ctx.rigid);
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
  const Vec3<L> n = normalize_or_zero(j.separation, length);
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
  const Vec3<L> n = normalize_or_zero(j.separation, length);
  const L k = axial_constraint_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                                    j.b.inv_inertia, j.r_b, n);
  const L axial = inverse_or_zero(k);

  // Spring or rod row: solved unless free, relaxed only when rigid.
  if constexpr (kUseBias ? F.row != RowKind::Free
                         : (F.row == RowKind::Any || F.row == RowKind::Rigid)) {
    const L cdot = dot(n, relative_velocity(j));
    const L accumulated = load<L>(g.impulse);
    RowCoefficients<L> co = load_coefficients<L>(g);
    if constexpr (kUseBias && (F.row == RowKind::Soft || F.row == RowKind::Any)) {
      co = with_absolute_spring(co, load<L>(g.spring_stiffness), load<L>(g.spring_damping), k,
                                ctx.h);
    }
    const L dp = bilateral_row_impulse<L, kUseBias, F.row>(
        cdot, length - load<L>(g.rest_length), k, axial, accumulated, co);
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
