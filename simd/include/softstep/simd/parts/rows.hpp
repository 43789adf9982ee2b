// How one constraint row turns its velocity error into an impulse, in each of the modes a
// part may be solved in (DESIGN.md, "The math in one place"):
//   rigid     a stiff spring capped by the sub-step rate while solving, no bias while relaxing;
//             the bias + feedback sum is bounded by max_correction_speed (bounded_bias);
//   soft      the row's own spring (hertz, damping ratio), solved once per sub-step, not relaxed;
//   free      no row at all (the caller does not call);
//   limit     one-sided (impulse >= 0), speculative ahead of contact, rigid when violated;
//   motor     no bias, drives J v to a target speed, |accumulated impulse| <= max impulse.
// Every function returns the change dP of the accumulated impulse; the caller accumulates and
// applies it, so a coupled clamp (a friction disk, a vector cap) can sit between the two.
#pragma once

#include "softstep/simd/joint_lanes.hpp"

namespace softstep::simd {

// The coefficients of a rigid or soft row for one sub-step (softness.hpp, talk names).
template <class L>
struct RowCoefficients {
  L bias_rate, mass_scale, impulse_scale, feedback, max_bias, relax_scale;
};

template <class L>
SOFTSTEP_INLINE RowCoefficients<L> load_coefficients(const SoftRowLanes<kWidth<L>>& g) {
  return {load<L>(g.bias_rate), load<L>(g.mass_scale), load<L>(g.impulse_scale),
          load<L>(g.feedback),  load<L>(g.max_bias),   load<L>(g.relax_scale)};
}

// A row's coefficients where its lane's spring is in absolute units (Spring::absolute: k in
// N/m or N m/rad, c in N s/m or N m s/rad, both 0 in a relative lane), from the row's
// K = 1/m_eff now: a = h (c + h k) K, bias_rate = k / (c + h k), mass_scale = a/(1+a),
// impulse_scale = 1/(1+a), feedback = 1/a (softness.hpp; the relative form is this with
// k = m_eff omega^2, c = 2 m_eff zeta omega). A per-lane select on k > 0 || c > 0, not a
// signature bit (no kernel variant more to compile): a relative lane gets `relative` back
// bit for bit.
template <class L>
SOFTSTEP_INLINE RowCoefficients<L> with_absolute_spring(const RowCoefficients<L>& relative,
                                                        const L& stiffness, const L& damping,
                                                        const L& k_row, float h) {
  const auto absolute = stiffness > L(0.0f) || damping > L(0.0f);
  const L hl(h);
  const L resistance = select(absolute, fmadd(hl, stiffness, damping), L(1.0f));  // c + h k > 0
  const L a = hl * resistance * k_row;
  const L inv_one_plus_a = L(1.0f) / (L(1.0f) + a);
  const auto stiff = absolute && a > L(0.0f);
  RowCoefficients<L> co = relative;
  co.bias_rate = select(absolute, stiffness / resistance, relative.bias_rate);
  co.mass_scale = select(absolute, L(1.0f) - inv_one_plus_a, relative.mass_scale);
  co.impulse_scale = select(absolute, inv_one_plus_a, relative.impulse_scale);
  co.feedback = select(stiff, L(1.0f) / select(stiff, a, L(1.0f)), relative.feedback);
  return co;
}

// What a rigid row solves with: the same values prepare_row_coefficients<Rigid> stores.
template <class L>
SOFTSTEP_INLINE RowCoefficients<L> rigid_coefficients(const SubstepContext& ctx) {
  return {L(ctx.rigid.bias_rate), L(ctx.rigid.mass_scale),     L(ctx.rigid.impulse_scale),
          L(ctx.rigid.feedback),  L(ctx.max_correction_speed), L(1.0f)};
}

// 1/k, or 0 where k is not positive (neither body can move along the row).
template <class L>
SOFTSTEP_INLINE L inverse_or_zero(const L& k) {
  const auto ok = k > L(0.0f);
  return select(ok, L(1.0f) / select(ok, k, L(1.0f)), L(0.0f));
}

// One bilateral row with error c, velocity error cdot, K = J M^-1 J^T = k and m_eff = 1/k.
// kRow: Rigid or Soft for a group known to be so, Any to switch per lane by the coefficients
// (max_bias +inf marks a spring, relax_scale 0 a row that is not relaxed).
template <class L, bool kUseBias, RowKind kRow>
SOFTSTEP_INLINE L bilateral_row_impulse(const L& cdot, const L& c, const L& k, const L& m_eff,
                                        const L& accumulated, const RowCoefficients<L>& co) {
  if constexpr (kUseBias) {
    L bias = co.bias_rate * c;
    if constexpr (kRow != RowKind::Soft) {
      bias = bounded_bias<L, kRow>(bias, co.feedback * k * accumulated, co.max_bias);
    }
    return fmadd(L(0.0f) - co.mass_scale * m_eff, cdot + bias,
                 L(0.0f) - co.impulse_scale * accumulated);
  } else if constexpr (kRow == RowKind::Rigid) {
    return L(-1.0f) * m_eff * cdot;  // relax_scale is 1: (0 - 1) m_eff cdot, as in Any
  } else {
    return (L(0.0f) - co.relax_scale) * m_eff * cdot;
  }
}

// One unilateral limit row (C >= 0 wanted, accumulated impulse >= 0). Ahead of contact
// (C > 0) it is speculative: the gap may close within one sub-step but not beyond, in solve
// and relax alike. Violated, it is a stiff row of softness `violated` (ctx.rigid for a length
// limit, ctx.limit for a joint's axis and angle limits) whose push is bounded by
// max_correction_speed.
template <class L, bool kUseBias>
SOFTSTEP_INLINE L limit_row_impulse(const L& cdot, const L& c, const L& k, const L& m_eff,
                                    const L& accumulated, const SubstepContext& ctx,
                                    const Softness<float>& violated) {
  const auto ahead = c > L(0.0f);
  L bias = select(ahead, c * L(ctx.inv_h), L(0.0f));
  L mass_scale(1.0f);
  L impulse_scale(0.0f);
  if constexpr (kUseBias) {
    // Only the pushing direction is bounded: bias_rate C + gamma' P >= -max_correction_speed
    // (see bounded_bias for why the sum and not the bias alone).
    const L fed_back = L(violated.feedback) * k * accumulated;
    const L rigid_bias =
        max_lanes(L(violated.bias_rate) * c + fed_back, L(0.0f) - L(ctx.max_correction_speed)) -
        fed_back;
    bias = select(ahead, bias, rigid_bias);
    mass_scale = select(ahead, mass_scale, L(violated.mass_scale));
    impulse_scale = select(ahead, impulse_scale, L(violated.impulse_scale));
  }
  const L raw =
      fmadd(L(0.0f) - mass_scale * m_eff, cdot + bias, L(0.0f) - impulse_scale * accumulated);
  const L next = max_lanes(accumulated + raw, L(0.0f));
  return next - accumulated;
}

// A motor row: drives cdot to `speed` with an accumulated impulse within +-max_impulse (the
// maximum force or torque times the sub-step). No position bias, the same in both passes.
template <class L>
SOFTSTEP_INLINE L motor_row_impulse(const L& cdot, const L& speed, const L& m_eff,
                                    const L& accumulated, const L& max_impulse) {
  const L wanted = accumulated + (L(0.0f) - m_eff) * (cdot - speed);
  return clamp_lanes(wanted, max_impulse) - accumulated;
}

}  // namespace softstep::simd
