// Weld joint, composed of parts: the rotation lock (3 angular rows holding frame_B on
// frame_A), then the point (3 linear rows). Each half rigid, soft (its own spring, per lane
// coefficients) or free (not run), as the group's signature says.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/point_part.hpp"

namespace softstep::simd {

inline constexpr std::uint32_t kWeldLinearSoft = 1u;
inline constexpr std::uint32_t kWeldLinearFree = 2u;
inline constexpr std::uint32_t kWeldAngularSoft = 4u;
inline constexpr std::uint32_t kWeldAngularFree = 8u;

template <int W>
struct alignas(kLaneAlign<W>) WeldJointGroup : FrameLanes<W> {
  SoftRowLanes<W> linear;
  SoftRowLanes<W> angular;
  float point_impulse[3][W];
  float lock_impulse[3][W];
};

template <class L>
SOFTSTEP_INLINE void prepare_weld_joints(WeldJointGroup<kWidth<L>>& g, const SubstepContext& ctx,
                                         std::uint32_t signature) {
  if (signature & kWeldLinearSoft)
    prepare_row_coefficients<L, JointFeatures{RowKind::Soft, false, false}>(g.linear, ctx);
  if (signature & kWeldAngularSoft)
    prepare_row_coefficients<L, JointFeatures{RowKind::Soft, false, false}>(g.angular, ctx);
}

template <class L>
SOFTSTEP_INLINE void warm_start_weld_joints(WeldJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                            std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  if (!(signature & kWeldAngularFree)) apply_angular_impulse(j, load3<L>(g.lock_impulse));
  if (!(signature & kWeldLinearFree)) warm_start_point(j, g.point_impulse);
  scatter_joint(g, bodies, j);
}

// A half runs in the solve unless free, and in the relax only when rigid.
inline constexpr bool weld_half_runs(std::uint32_t signature, std::uint32_t soft,
                                     std::uint32_t free, bool use_bias) {
  return !(signature & free) && (use_bias || !(signature & soft));
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_weld_joints(WeldJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                       const SubstepContext& ctx, std::uint32_t signature) {
  const bool angular = weld_half_runs(signature, kWeldAngularSoft, kWeldAngularFree, kUseBias);
  const bool linear = weld_half_runs(signature, kWeldLinearSoft, kWeldLinearFree, kUseBias);
  if (!angular && !linear) return;
  JointBodies<L> j = gather_joint<L>(g, bodies);
  if (angular) {
    const Frames<L> f = current_frames(g, j);
    const Vec3<L> error = rotation_error(f.a, f.b);
    if (signature & kWeldAngularSoft) {
      solve_angular_lock3<L, kUseBias, RowKind::Soft>(j, error, g.lock_impulse,
                                                      load_coefficients<L>(g.angular));
    } else {
      solve_angular_lock3<L, kUseBias, RowKind::Rigid>(j, error, g.lock_impulse,
                                                       rigid_coefficients<L>(ctx));
    }
  }
  if (linear) {
    if (signature & kWeldLinearSoft) {
      solve_point<L, kUseBias, RowKind::Soft>(j, g.point_impulse, load_coefficients<L>(g.linear));
    } else {
      solve_point<L, kUseBias, RowKind::Rigid>(j, g.point_impulse, rigid_coefficients<L>(ctx));
    }
  }
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
