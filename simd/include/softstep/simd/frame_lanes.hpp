// What the angular joints add to the anchor lanes: each body's joint frame at the step start,
// and the controls of a joint's one free axis (limit, motor, spring; axis_controls.hpp in the
// public API), solved by the same row modes whatever the axis is (an angle, a translation).
#pragma once

#include "softstep/simd/angles.hpp"
#include "softstep/simd/parts/rows.hpp"

namespace softstep::simd {

// The joint frames of A and B in the world at the step start (x, y, z, w), written by core's
// anchor pass in double; the kernels turn them by each body's rotation since (dq).
template <int W>
struct alignas(kLaneAlign<W>) FrameLanes : AnchorLanes<W> {
  float frame_a[4][W];
  float frame_b[4][W];
};

template <class L>
SOFTSTEP_INLINE Quat<L> load_quat(const float (&q)[4][kWidth<L>]) {
  return {load<L>(q[0]), load<L>(q[1]), load<L>(q[2]), load<L>(q[3])};
}

// Both frames now: frame = dq * frame at the step start.
template <class L>
struct Frames {
  Quat<L> a, b;
};
template <class L, int W>
SOFTSTEP_INLINE Frames<L> current_frames(const FrameLanes<W>& g, const JointBodies<L>& j) {
  return {multiply(j.a.dq, load_quat<L>(g.frame_a)), multiply(j.b.dq, load_quat<L>(g.frame_b))};
}

// Which of a free axis's controls a joint has: the bits of its signature (runs are uniform in
// them, so a kernel branches once per group).
inline constexpr std::uint32_t kAxisLimit = 1u;
inline constexpr std::uint32_t kAxisMotor = 2u;
inline constexpr std::uint32_t kAxisSpring = 4u;

// A free axis's controls. Positions are measured as `position` (what the kernel computes now)
// plus a per-lane gap written at the step start, so that an angle kept unwrapped in double
// (revolute) enters the float kernel only as small differences.
template <int W>
struct alignas(kLaneAlign<W>) AxisControlLanes {
  float lower_gap[W];   // C_lower = position + lower_gap >= 0
  float upper_gap[W];   // C_upper = upper_gap - position >= 0
  float spring_gap[W];  // C_spring = position + spring_gap
  float motor_speed[W];
  float motor_max[W];  // N or N m
  float spring_hertz[W];  // relative units (0 in a lane whose spring is absolute)
  float spring_zeta[W];
  // Absolute units (Spring::absolute): k in N/m or N m/rad, c in N s/m or N m s/rad; both 0
  // in a lane whose spring is relative. A lane with either > 0 converts with its row's K in
  // each sub-step (absolute_spring_coefficients); the others keep the prepared coefficients.
  float spring_stiffness[W];
  float spring_damping[W];
  // Prepared once per step:
  float spring_bias_rate[W];
  float spring_mass_scale[W];
  float spring_impulse_scale[W];
  float motor_max_impulse[W];  // motor_max * h
  // Accumulated impulses of the current sub-step (positive pushes towards larger positions,
  // the upper limit's towards smaller ones):
  float lower_impulse[W];
  float upper_impulse[W];
  float motor_impulse[W];
  float spring_impulse[W];
};

template <class L>
SOFTSTEP_INLINE void prepare_axis_controls(AxisControlLanes<kWidth<L>>& g,
                                           const SubstepContext& ctx, std::uint32_t signature) {
  if (signature & kAxisSpring) {
    const Softness<L> s = make_softness(load<L>(g.spring_hertz), load<L>(g.spring_zeta), ctx.h);
    store_lanes(g.spring_bias_rate, s.bias_rate);
    store_lanes(g.spring_mass_scale, s.mass_scale);
    store_lanes(g.spring_impulse_scale, s.impulse_scale);
  }
  if (signature & kAxisMotor) store_lanes(g.motor_max_impulse, load<L>(g.motor_max) * L(ctx.h));
}

// The impulse the controls hold, along the axis (for the warm start).
template <class L>
SOFTSTEP_INLINE L axis_controls_impulse(const AxisControlLanes<kWidth<L>>& g,
                                        std::uint32_t signature) {
  L total(0.0f);
  if (signature & kAxisSpring) total = total + load<L>(g.spring_impulse);
  if (signature & kAxisMotor) total = total + load<L>(g.motor_impulse);
  if (signature & kAxisLimit) total = total + (load<L>(g.lower_impulse) - load<L>(g.upper_impulse));
  return total;
}

// Spring (solve pass only: springs are not relaxed), motor, then the two limits. `axis` gives
// the row's velocity, K and m_eff (.cdot(), .k, .m_eff) and applies an impulse along the axis
// (.apply(impulse), which also refreshes cdot).
template <class L, bool kUseBias, class Axis>
SOFTSTEP_INLINE void solve_axis_controls(AxisControlLanes<kWidth<L>>& g, std::uint32_t signature,
                                         const L& position, Axis& axis, const SubstepContext& ctx) {
  if constexpr (kUseBias) {
    if (signature & kAxisSpring) {
      const L accumulated = load<L>(g.spring_impulse);
      const RowCoefficients<L> relative{load<L>(g.spring_bias_rate),
                                        load<L>(g.spring_mass_scale),
                                        load<L>(g.spring_impulse_scale),
                                        L(0.0f),
                                        L(0.0f),
                                        L(0.0f)};
      const RowCoefficients<L> co = with_absolute_spring(
          relative, load<L>(g.spring_stiffness), load<L>(g.spring_damping), axis.k, ctx.h);
      const L dp = bilateral_row_impulse<L, true, RowKind::Soft>(
          axis.cdot(), position + load<L>(g.spring_gap), axis.k, axis.m_eff, accumulated, co);
      store_lanes(g.spring_impulse, accumulated + dp);
      axis.apply(dp);
    }
  }
  if (signature & kAxisMotor) {
    const L accumulated = load<L>(g.motor_impulse);
    const L dp = motor_row_impulse(axis.cdot(), load<L>(g.motor_speed), axis.m_eff, accumulated,
                                   load<L>(g.motor_max_impulse));
    store_lanes(g.motor_impulse, accumulated + dp);
    axis.apply(dp);
  }
  if (signature & kAxisLimit) {
    {
      const L accumulated = load<L>(g.lower_impulse);
      const L dp = limit_row_impulse<L, kUseBias>(axis.cdot(), position + load<L>(g.lower_gap),
                                                  axis.k, axis.m_eff, accumulated, ctx, ctx.limit);
      store_lanes(g.lower_impulse, accumulated + dp);
      axis.apply(dp);
    }
    {
      const L accumulated = load<L>(g.upper_impulse);
      const L dp =
          limit_row_impulse<L, kUseBias>(L(0.0f) - axis.cdot(), load<L>(g.upper_gap) - position,
                                         axis.k, axis.m_eff, accumulated, ctx, ctx.limit);
      store_lanes(g.upper_impulse, accumulated + dp);
      axis.apply(L(0.0f) - dp);
    }
  }
}

template <int W>
void clear_axis_controls(AxisControlLanes<W>& g) {
  for (float* p : {g.lower_impulse, g.upper_impulse, g.motor_impulse, g.spring_impulse}) {
    for (int i = 0; i < W; ++i) p[i] = 0.0f;
  }
}

}  // namespace softstep::simd
