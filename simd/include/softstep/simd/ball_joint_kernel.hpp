// Ball joint: the point part alone (parts/point_part.hpp): three rows that keep anchor A and
// anchor B together, rigid, soft or free. One source for every lane width.
#pragma once

#include "softstep/simd/parts/point_part.hpp"

namespace softstep::simd {

template <int W>
struct alignas(kLaneAlign<W>) BallJointGroup : JointLanes<W> {
  // Accumulated impulse of the current sub-step, N s, world frame: the warm start.
  float impulse[3][W];
};

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
    warm_start_point(j, g.impulse);
    scatter_joint(g, bodies, j);
  }
}

// kUseBias = true: the soft, biased solve. false: the rigid relax pass (no bias, springs
// untouched: a spring's one soft solve per sub-step is exactly implicit Euler, talk 2:3:2).
template <class L, bool kUseBias, JointFeatures F = kGeneralKernel>
SOFTSTEP_INLINE void solve_ball_joints(BallJointGroup<kWidth<L>>& g, const BodyArrays& bodies) {
  if constexpr (kUseBias ? !ball_needs_solve(F) : !ball_needs_relax(F)) return;
  JointBodies<L> j = gather_joint<L>(g, bodies);
  solve_point<L, kUseBias, F.row>(j, g.impulse, load_coefficients<L>(g));
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
