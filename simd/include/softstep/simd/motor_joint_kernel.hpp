// Motor joint: drives B's frame towards a target frame held by A (animation-driven ragdolls,
// mouse dragging), as a weld whose pulls are capped. Parts, in order: the rotation lock
// (3 angular rows, the accumulated torque impulse capped at max_torque h in length), then the
// point (3 linear rows, capped at max_force h). Each half corrects rigidly or softly (its own
// spring, per lane coefficients), as the group's signature says. Neither relaxes: the rows
// are a drive, not a lock, and a relax pass (no bias) would take back the velocity they give
// (a capped rigid drive would only creep). A rigid half so drives B at up to
// max_correction_speed, accelerating and braking within its caps.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/point_part.hpp"
#include "softstep/simd/weld_joint_kernel.hpp"

namespace softstep::simd {

inline constexpr std::uint32_t kMotorLinearSoft = 1u;
inline constexpr std::uint32_t kMotorAngularSoft = 2u;

// A weld's lanes (frames, the two halves' springs, point and rotation impulses) and the caps.
template <int W>
struct alignas(kLaneAlign<W>) MotorJointGroup : WeldJointGroup<W> {
  float max_force[W];   // N
  float max_torque[W];  // N m
  // Prepared once per step: the caps times the sub-step.
  float max_linear_impulse[W];
  float max_angular_impulse[W];
};

template <class L>
SOFTSTEP_INLINE void prepare_motor_joints(MotorJointGroup<kWidth<L>>& g, const SubstepContext& ctx,
                                          std::uint32_t signature) {
  if (signature & kMotorLinearSoft)
    prepare_row_coefficients<L, JointFeatures{RowKind::Soft, false, false}>(g.linear, ctx);
  if (signature & kMotorAngularSoft)
    prepare_row_coefficients<L, JointFeatures{RowKind::Soft, false, false}>(g.angular, ctx);
  store_lanes(g.max_linear_impulse, load<L>(g.max_force) * L(ctx.h));
  store_lanes(g.max_angular_impulse, load<L>(g.max_torque) * L(ctx.h));
}

template <class L>
SOFTSTEP_INLINE void warm_start_motor_joints(MotorJointGroup<kWidth<L>>& g,
                                             const BodyArrays& bodies, std::uint32_t) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  apply_angular_impulse(j, load3<L>(g.lock_impulse));
  warm_start_point(j, g.point_impulse);
  scatter_joint(g, bodies, j);
}

namespace detail {
// One capped 3-row block: the block's impulse change (block3_impulse) cut back so that the
// accumulated impulse stays within max_impulse.
template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE Vec3<L> capped_block(const Vec3<L>& cdot, const Vec3<L>& error,
                                     const Mat3Sym<L>& k, float (&impulse)[3][kWidth<L>],
                                     const RowCoefficients<L>& co, const L& max_impulse) {
  const Vec3<L> accumulated = load3<L>(impulse);
  const Vec3<L> dp = capped_change(
      accumulated,
      block3_impulse<L, kUseBias, kRow>(cdot, error, k, inverse_or_zero(k), accumulated, co),
      max_impulse);
  store3<L>(impulse, accumulated + dp);
  return dp;
}

template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE void solve_motor_rotation(MotorJointGroup<kWidth<L>>& g, JointBodies<L>& j,
                                          const RowCoefficients<L>& co) {
  const Frames<L> f = current_frames(g, j);
  const Vec3<L> dp = capped_block<L, kUseBias, kRow>(
      relative_angular_velocity(j), rotation_error(f.a, f.b), j.a.inv_inertia + j.b.inv_inertia,
      g.lock_impulse, co, load<L>(g.max_angular_impulse));
  apply_angular_impulse(j, dp);
}

template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE void solve_motor_point(MotorJointGroup<kWidth<L>>& g, JointBodies<L>& j,
                                       const RowCoefficients<L>& co) {
  const Mat3Sym<L> k = point_constraint_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                                             j.b.inv_inertia, j.r_b);
  const Vec3<L> dp = capped_block<L, kUseBias, kRow>(relative_velocity(j), j.separation, k,
                                                     g.point_impulse, co,
                                                     load<L>(g.max_linear_impulse));
  apply_impulse(j, dp);
}
}  // namespace detail

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_motor_joints(MotorJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                        const SubstepContext& ctx, std::uint32_t signature) {
  if constexpr (!kUseBias) return;  // see the top
  JointBodies<L> j = gather_joint<L>(g, bodies);
  {
    if (signature & kMotorAngularSoft) {
      detail::solve_motor_rotation<L, kUseBias, RowKind::Soft>(g, j,
                                                              load_coefficients<L>(g.angular));
    } else {
      detail::solve_motor_rotation<L, kUseBias, RowKind::Rigid>(g, j, rigid_coefficients<L>(ctx));
    }
  }
  {
    if (signature & kMotorLinearSoft) {
      detail::solve_motor_point<L, kUseBias, RowKind::Soft>(g, j, load_coefficients<L>(g.linear));
    } else {
      detail::solve_motor_point<L, kUseBias, RowKind::Rigid>(g, j, rigid_coefficients<L>(ctx));
    }
  }
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
