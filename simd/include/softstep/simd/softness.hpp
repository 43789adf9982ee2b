// Softness coefficients of a row for one sub-step h, from the talk (slides 2:3:2, 3:3):
//   omega = 2 pi hertz,  k = m_eff omega^2,  c = 2 m_eff zeta omega
//   gamma = 1/(c + h k),  beta = h k/(c + h k)
// written in the sequential-impulse form that needs no m_eff (it cancels):
//   a = h omega (2 zeta + h omega)
//   bias_rate = omega / (2 zeta + h omega)   (= beta / h)
//   mass_scale = a / (1 + a),  impulse_scale = 1 / (1 + a)
//   dP = -mass_scale * m_eff * (J v + bias_rate * C) - impulse_scale * P
// and the velocity the accumulated impulse feeds back, gamma' P with gamma' = gamma / h:
//   gamma' = feedback * K,  feedback = 1 / a   (K = 1 / m_eff; a matrix for a 3-row block)
#pragma once

#include <numbers>

#include "softstep/simd/lanes.hpp"

namespace softstep::simd {

template <class L>
struct Softness {
  L bias_rate;      // 1/s: fraction of the position error removed per second
  L mass_scale;     // in [0, 1): how much of the rigid impulse is applied
  L impulse_scale;  // in (0, 1]: how much of the accumulated impulse is given back
  L feedback;       // 1/a: gamma' = feedback * K, the softness as a velocity per impulse
};

// hertz > 0 and zeta >= 0 are the caller's promise (validated at the API). hertz == 0 is a
// spring with no stiffness: the row applies nothing.
template <class L>
SOFTSTEP_INLINE Softness<L> make_softness(const L& hertz, const L& zeta, float h) {
  const L omega = L(2.0f * std::numbers::pi_v<float>) * hertz;
  const L hl(h);
  const L denom = fmadd(hl, omega, L(2.0f) * zeta);  // 2 zeta + h omega
  const auto active = hertz > L(0.0f);
  const L safe_denom = select(active, denom, L(1.0f));
  const L a = hl * omega * safe_denom;
  const L inv_one_plus_a = L(1.0f) / (L(1.0f) + a);
  const auto stiff = active && a > L(0.0f);
  // mass_scale = a / (1 + a), written as 1 - 1/(1 + a): the same where both are defined, and
  // 1 (not inf * 0) when a overflows for an extreme frequency. For the slowest rows that
  // difference cancels: at a = 1.05e-7 (rigid_hertz 1e-6) it rounded to 1.19e-7, so that
  // mass_scale * feedback, which must be 1 / (1 + a) < 1, was 1.14 and every solve iteration
  // grew the row's accumulated impulse by 14 % (a corner sampler's worlds, NaN within a
  // second). Its rounding passes 1 below a ~ 2.4e-4 (6e-8 / a > a); below 1e-3 a / (1 + a)
  // is used, and above, the old form keeps every spring's trajectory bit for bit (a 4 Hz
  // spring at 1/240 s has a = 0.07; the golden hashes hold).
  // Spring.KernelSoftnessGivesBackLessThanItHoldsAtEveryFrequency.
  const L mass_scale = select(a < L(1e-3f), a * inv_one_plus_a, L(1.0f) - inv_one_plus_a);
  return {select(active, omega / safe_denom, L(0.0f)), select(active, mass_scale, L(0.0f)),
          select(active, inv_one_plus_a, L(0.0f)),
          select(stiff, L(1.0f) / select(stiff, a, L(1.0f)), L(0.0f))};
}

}  // namespace softstep::simd
