// Revolute joint (hinge), composed of parts, solved in this order (the hardest rows last):
//   spring, motor, lower and upper limit   angular axis rows about A's hinge axis z_A
//   hinge lock                             2 angular rows keeping B's axis z_B along z_A
//   point                                  3 linear rows keeping the anchors together
// The hinge angle is the twist of the relative rotation frame_A^-1 frame_B about z: the kernel
// measures its change since the step start (at most half a turn, wrap_angle) and adds the
// lanes' step-start gaps, which core computes from the unwrapped angle in double.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/point_part.hpp"

namespace softstep::simd {

template <int W>
struct alignas(kLaneAlign<W>) RevoluteJointGroup : FrameLanes<W> {
  AxisControlLanes<W> axis;
  float angle_start[W];  // the hinge angle at the step start, wrapped into [-pi, pi]
  float point_impulse[3][W];
  float lock_impulse[2][W];
};

namespace detail {
template <class L>
struct HingeNow {
  Vec3<L> axis_a;  // z_A
  HingeLock<L> lock;
  L angle_change;  // since the step start, rad
};

template <class L>
SOFTSTEP_INLINE HingeNow<L> hinge_now(const RevoluteJointGroup<kWidth<L>>& g,
                                      const JointBodies<L>& j) {
  const Frames<L> f = current_frames(g, j);
  const Vec3<L> z_a = axis_z(f.a);
  const L angle = twist_angle_z(multiply(conjugate(f.a), f.b));
  return {z_a, hinge_lock(axis_x(f.a), axis_y(f.a), axis_z(f.b)),
          wrap_angle(angle - load<L>(g.angle_start))};
}

// The angular axis row as solve_axis_controls wants it.
template <class L>
struct HingeAxis {
  JointBodies<L>& j;
  AngularAxis<L> row;
  L k, m_eff;
  L cdot() const { return row.cdot; }
  void apply(const L& impulse) { apply_axis_torque(j, row, impulse); }
};
}  // namespace detail

template <class L>
SOFTSTEP_INLINE void prepare_revolute_joints(RevoluteJointGroup<kWidth<L>>& g,
                                             const SubstepContext& ctx, std::uint32_t signature) {
  prepare_axis_controls<L>(g.axis, ctx, signature);
}

template <class L>
SOFTSTEP_INLINE void warm_start_revolute_joints(RevoluteJointGroup<kWidth<L>>& g,
                                                const BodyArrays& bodies, std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::HingeNow<L> h = detail::hinge_now<L>(g, j);
  if (signature != 0)
    apply_angular_impulse(j, axis_controls_impulse<L>(g.axis, signature) * h.axis_a);
  warm_start_hinge_lock(j, h.lock, g.lock_impulse);
  warm_start_point(j, g.point_impulse);
  scatter_joint(g, bodies, j);
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_revolute_joints(RevoluteJointGroup<kWidth<L>>& g,
                                           const BodyArrays& bodies, const SubstepContext& ctx,
                                           std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::HingeNow<L> h = detail::hinge_now<L>(g, j);
  if (signature != 0) {
    const AngularAxis<L> row = angular_axis(j, h.axis_a);
    detail::HingeAxis<L> axis{j, row, row.k, row.m_eff};
    solve_axis_controls<L, kUseBias>(g.axis, signature, h.angle_change, axis, ctx);
  }
  const RowCoefficients<L> rigid = rigid_coefficients<L>(ctx);
  solve_hinge_lock<L, kUseBias>(j, h.lock, g.lock_impulse, rigid);
  solve_point<L, kUseBias, RowKind::Rigid>(j, g.point_impulse, rigid);
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
