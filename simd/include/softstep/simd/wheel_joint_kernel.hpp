// Wheel joint (a car's suspension and axle), A = chassis, B = wheel, composed of parts, solved
// in this order (the hardest rows last):
//   suspension spring, lower and upper travel limit   axis rows along A's z (axis_part.hpp)
//   spin motor                                        1 angular row about the steered axle
//   lateral lock                                      2 linear rows along the steered axle and
//                                                     the forward direction (dual_axis_part.hpp)
//   axle lock                                         2 angular rows keeping B's axle x_B on
//                                                     the steered axle (angular_parts.hpp)
// The steered axle is A's x turned about A's z by the steering angle s:
//   e = cos s x_A + sin s y_A,   forward f = z_A x e = cos s y_A - sin s x_A.
// The travel is (anchor B - anchor A) . z_A, as a slider's translation.
//
// The spring is not relative to the row's effective mass (which the light wheel dominates):
// its stiffness and damping come from the sprung mass m_s the lanes carry,
//   k = m_s omega^2,  c = 2 m_s zeta omega,
// and the row is the talk's soft constraint with those k and c:
//   gamma' = 1 / (h (c + h k)),  bias_rate = k / (c + h k),
//   dP = -(J v + bias_rate C + gamma' P) / (K + gamma')
// (with k = m_eff omega^2 this is the usual mass_scale / impulse_scale form).
// The soft step is implicit Euler, whose own damping adds h omega / 2 to the damping ratio
// (8 % of a 0.3 ratio at 2 Hz, 60 Hz and 4 sub-steps): the damping is lowered by h k / 2 to
// give it back (c' = max(0, c - h k / 2)), so that the car's bounce decays with the ratio the
// designer set (within 1 % of it, and the frequency within 1 %, at those settings). Below
// h omega / 2 the ratio cannot be reached (c' = 0).
// A spring in absolute units (Spring::absolute) gives k and c itself (the lanes'
// spring_stiffness and spring_damping, the sprung mass unused) and takes the same path,
// the same c' included: absolute(m_s omega^2, 2 m_s zeta omega) is the relative spring.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/dual_axis_part.hpp"

namespace softstep::simd {

// The signature's bits are the axis controls' (frame_lanes.hpp): kAxisLimit the travel
// limits (solved by solve_axis_controls), kAxisSpring the suspension spring and kAxisMotor the
// spin motor, both solved here (the spring with the sprung mass, the motor about the axle).
template <int W>
struct alignas(kLaneAlign<W>) WheelJointGroup : FrameLanes<W> {
  // Limits, the spring's gap and impulse, the motor's speed, max torque and impulse; its
  // spring_bias_rate holds bias_rate and spring_mass_scale holds gamma' (see the top).
  AxisControlLanes<W> axis;
  float sprung_mass[W];  // kg
  float steer_cos[W];
  float steer_sin[W];
  float lateral_impulse[2][W];
  float lock_impulse[2][W];
};

// k and c of the sprung mass into the row's bias_rate and gamma' (prepared once per step).
template <class L>
SOFTSTEP_INLINE void prepare_sprung_spring(AxisControlLanes<kWidth<L>>& g, const L& sprung_mass,
                                           const SubstepContext& ctx) {
  const L omega = L(2.0f * std::numbers::pi_v<float>) * load<L>(g.spring_hertz);
  const L h(ctx.h);
  const L absolute_stiffness = load<L>(g.spring_stiffness);
  const L absolute_damping = load<L>(g.spring_damping);
  const auto absolute = absolute_stiffness > L(0.0f) || absolute_damping > L(0.0f);
  // A per-lane select: a relative lane's k and c are computed as before, bit for bit.
  const L stiffness = select(absolute, absolute_stiffness, sprung_mass * omega * omega);
  const L half_step_stiffness = L(0.5f) * h * stiffness;
  const L damping = max_lanes(
      select(absolute, absolute_damping, L(2.0f) * sprung_mass * load<L>(g.spring_zeta) * omega) -
          half_step_stiffness,
      L(0.0f));
  const L resistance = fmadd(h, stiffness, damping);  // c' + h k, > 0 (validated)
  const auto ok = resistance > L(0.0f);
  const L safe = select(ok, resistance, L(1.0f));
  store_lanes(g.spring_bias_rate, select(ok, stiffness / safe, L(0.0f)));
  store_lanes(g.spring_mass_scale, select(ok, L(1.0f) / (h * safe), L(0.0f)));
}

// The soft row of a spring with its own k and c (gamma', bias_rate as prepared above).
template <class L>
SOFTSTEP_INLINE L sprung_row_impulse(const L& cdot, const L& c, const L& k, const L& gamma,
                                     const L& bias_rate, const L& accumulated) {
  const L denom = k + gamma;
  const auto ok = denom > L(0.0f);
  const L velocity_error = fmadd(gamma, accumulated, fmadd(bias_rate, c, cdot));
  return select(ok, (L(0.0f) - velocity_error) / select(ok, denom, L(1.0f)), L(0.0f));
}

namespace detail {
template <class L>
struct WheelNow {
  Vec3<L> up;       // z_A, the suspension axis
  Vec3<L> axle;     // e, the steered axle
  Vec3<L> forward;  // f = z_A x e
  HingeLock<L> lock;
};

template <class L>
SOFTSTEP_INLINE WheelNow<L> wheel_now(const WheelJointGroup<kWidth<L>>& g,
                                      const JointBodies<L>& j) {
  const Frames<L> f = current_frames(g, j);
  const Vec3<L> x_a = axis_x(f.a), y_a = axis_y(f.a);
  const L c = load<L>(g.steer_cos), s = load<L>(g.steer_sin);
  const Vec3<L> axle = mul_add(s, y_a, c * x_a);
  const Vec3<L> forward = mul_add(L(0.0f) - s, x_a, c * y_a);
  const Vec3<L> up = axis_z(f.a);
  // The lock's two rows are perpendicular to the axle: the suspension axis and the forward.
  return {up, axle, forward, hinge_lock(up, forward, axis_x(f.b))};
}
}  // namespace detail

template <class L>
SOFTSTEP_INLINE void prepare_wheel_joints(WheelJointGroup<kWidth<L>>& g, const SubstepContext& ctx,
                                          std::uint32_t signature) {
  prepare_axis_controls<L>(g.axis, ctx, signature & ~kAxisSpring);  // the motor's max impulse
  if (signature & kAxisSpring) prepare_sprung_spring<L>(g.axis, load<L>(g.sprung_mass), ctx);
}

template <class L>
SOFTSTEP_INLINE void warm_start_wheel_joints(WheelJointGroup<kWidth<L>>& g,
                                             const BodyArrays& bodies, std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::WheelNow<L> w = detail::wheel_now<L>(g, j);
  L along = axis_controls_impulse<L>(g.axis, signature & kAxisLimit);
  if (signature & kAxisSpring) along = along + load<L>(g.axis.spring_impulse);
  if (signature & (kAxisSpring | kAxisLimit))
    apply_slider_impulse(j, slider_axis(j, w.up), along);
  if (signature & kAxisMotor)
    apply_angular_impulse(j, load<L>(g.axis.motor_impulse) * w.axle);
  warm_start_dual_axis(j, w.axle, w.forward, g.lateral_impulse);
  warm_start_hinge_lock(j, w.lock, g.lock_impulse);
  scatter_joint(g, bodies, j);
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_wheel_joints(WheelJointGroup<kWidth<L>>& g, const BodyArrays& bodies,
                                        const SubstepContext& ctx, std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  const detail::WheelNow<L> w = detail::wheel_now<L>(g, j);
  if (signature & (kAxisSpring | kAxisLimit)) {
    const SliderAxis<L> row = slider_axis(j, w.up);
    SlideAxis<L> axis{j, row, row.k, row.m_eff, slider_velocity(j, row)};
    const L travel = dot(w.up, j.separation);
    if constexpr (kUseBias) {
      if (signature & kAxisSpring) {  // springs are not relaxed
        const L accumulated = load<L>(g.axis.spring_impulse);
        const L dp = sprung_row_impulse(axis.cdot(), travel + load<L>(g.axis.spring_gap), row.k,
                                        load<L>(g.axis.spring_mass_scale),
                                        load<L>(g.axis.spring_bias_rate), accumulated);
        store_lanes(g.axis.spring_impulse, accumulated + dp);
        axis.apply(dp);
      }
    }
    solve_axis_controls<L, kUseBias>(g.axis, signature & kAxisLimit, travel, axis, ctx);
  }
  if (signature & kAxisMotor) {
    AngularAxis<L> spin = angular_axis(j, w.axle);
    const L accumulated = load<L>(g.axis.motor_impulse);
    const L dp = motor_row_impulse(spin.cdot, load<L>(g.axis.motor_speed), spin.m_eff, accumulated,
                                   load<L>(g.axis.motor_max_impulse));
    store_lanes(g.axis.motor_impulse, accumulated + dp);
    apply_axis_torque(j, spin, dp);
  }
  const RowCoefficients<L> rigid = rigid_coefficients<L>(ctx);
  solve_dual_axis<L, kUseBias>(j, w.axle, w.forward, g.lateral_impulse, rigid);
  solve_hinge_lock<L, kUseBias>(j, w.lock, g.lock_impulse, rigid);
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
