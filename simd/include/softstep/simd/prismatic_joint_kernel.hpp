// Prismatic joint (slider), composed of parts, solved in this order (the hardest rows last):
//   spring, motor, lower and upper limit   axis rows along A's slide axis z_A (axis_part.hpp)
//   lateral lock                           2 linear rows along x_A and y_A (dual_axis_part.hpp)
//   rotation lock                          3 angular rows holding frame_B on frame_A
// The translation is (anchor B - anchor A) . z_A.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/dual_axis_part.hpp"

namespace softstep::simd {

template <int W>
struct alignas(kLaneAlign<W>) PrismaticJointGroup : FrameLanes<W> {
  AxisControlLanes<W> axis;
  float lateral_impulse[2][W];
  float lock_impulse[3][W];
};

namespace detail {
template <class L>
struct SliderNow {
  Vec3<L> x_a, y_a, z_a;
  Vec3<L> rotation_error;
};

template <class L>
SOFTSTEP_INLINE SliderNow<L> slider_now(const PrismaticJointGroup<kWidth<L>>& g,
                                        const JointBodies<L>& j) {
  const Frames<L> f = current_frames(g, j);
  return {axis_x(f.a), axis_y(f.a), axis_z(f.a), rotation_error(f.a, f.b)};
}
}  // namespace detail

template <class L>
SOFTSTEP_INLINE void prepare_prismatic_joints(PrismaticJointGroup<kWidth<L>>& g,
                                              const SubstepContext& ctx, std::uint32_t signature) {
  prepare_axis_controls<L>(g.axis, ctx, signature);
}

template <class L>
SOFTSTEP_INLINE void warm_start_prismatic_joints(PrismaticJointGroup<kWidth<L>>& g,
                                                 const BodyArrays& bodies,
                                                 std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::SliderNow<L> s = detail::slider_now<L>(g, j);
  if (signature != 0) {
    apply_slider_impulse(j, slider_axis(j, s.z_a), axis_controls_impulse<L>(g.axis, signature));
  }
  warm_start_dual_axis(j, s.x_a, s.y_a, g.lateral_impulse);
  apply_angular_impulse(j, load3<L>(g.lock_impulse));
  scatter_joint(g, bodies, j);
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_prismatic_joints(PrismaticJointGroup<kWidth<L>>& g,
                                            const BodyArrays& bodies, const SubstepContext& ctx,
                                            std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::SliderNow<L> s = detail::slider_now<L>(g, j);
  if (signature != 0) {
    const SliderAxis<L> row = slider_axis(j, s.z_a);
    SlideAxis<L> axis{j, row, row.k, row.m_eff, slider_velocity(j, row)};
    solve_axis_controls<L, kUseBias>(g.axis, signature, dot(s.z_a, j.separation), axis, ctx);
  }
  const RowCoefficients<L> rigid = rigid_coefficients<L>(ctx);
  solve_dual_axis<L, kUseBias>(j, s.x_a, s.y_a, g.lateral_impulse, rigid);
  solve_angular_lock3<L, kUseBias, RowKind::Rigid>(j, s.rotation_error, g.lock_impulse, rigid);
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
