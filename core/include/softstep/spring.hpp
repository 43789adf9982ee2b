// How stiff a constraint is. Designers never type a stiffness: they give a frequency and a
// damping ratio (talk, part 3), or a response time in frames and how much it may oscillate
// (slide 3:3:1). The effective mass the constraint sees is computed by the solver, so the
// same Spring behaves the same on a 1 g body and on a 1 t body.
#pragma once

#include <limits>

namespace softstep {

// How much a designer-tuned spring may oscillate (talk 3:3:1).
enum class Oscillation {
  Free,  // damping ratio 0: oscillates without decay
  Some,  // damping ratio 0.5: a few visible, decaying oscillations
  None,  // damping ratio 1: critically damped, no overshoot
};

// The soft-constraint coefficients for one time step, in the talk's names.
struct SoftCoefficients {
  double gamma;          // = ODE's CFM = 1/(c + h k), s/kg
  double beta;           // = ODE's ERP, dimensionless, in [0, 1]
  double bias_rate;      // beta / h, 1/s
  double mass_scale;     // a / (1 + a)
  double impulse_scale;  // 1 / (1 + a)
};

struct Spring {
  // Oscillation frequency, Hz. +infinity: rigid. 0: no spring at all (free).
  double hertz = std::numeric_limits<double>::infinity();
  // Damping ratio zeta, dimensionless: 0 undamped, 1 critically damped, > 1 overdamped.
  double damping_ratio = 0.0;

  static Spring rigid() { return {}; }
  static Spring free() { return {0.0, 0.0}; }
  static Spring soft(double hertz, double damping_ratio) { return {hertz, damping_ratio}; }
  // Talk 3:3:1: a response within `frames` frames of a `frame_rate` Hz game (hertz =
  // frame_rate / frames), with an oscillation choice. frames and frame_rate finite and > 0.
  // Each helper throws InvalidArgument (errors.hpp) naming the argument for input no spring
  // has, instead of returning NaN or a rigid spring.
  static Spring designer(double frames, Oscillation oscillation, double frame_rate = 60.0);
  // From a stiffness k (N/m) and damping c (N s/m) as seen by a mass `effective_mass` (kg):
  // omega = sqrt(k/m), zeta = c / (2 m omega) (talk 1:1:2). k = 0 gives a free spring.
  // k, c finite and >= 0; effective_mass finite and > 0.
  static Spring from_stiffness(double k, double c, double effective_mass);
  // From ODE's ERP and CFM for a step h, as seen by an effective mass (talk 2:3:2 inverted:
  // k = ERP / (h CFM), c = (1 - ERP) / CFM). ERP in [0, 1]; CFM, effective_mass and h finite
  // and > 0.
  static Spring from_erp_cfm(double erp, double cfm, double effective_mass, double h);

  bool is_rigid() const { return hertz == std::numeric_limits<double>::infinity(); }
  bool is_free() const { return hertz == 0.0; }

  double stiffness(double effective_mass) const;  // k = m omega^2, N/m
  double damping(double effective_mass) const;    // c = 2 m zeta omega, N s/m
  // gamma/beta (= CFM/ERP) and the solver's coefficients for step h as seen by an effective
  // mass. A rigid spring gives gamma = 0, beta = 1.
  SoftCoefficients coefficients(double effective_mass, double h) const;
};

}  // namespace softstep
