// How stiff a constraint is. Designers never type a stiffness: they give a frequency and a
// damping ratio (talk, part 3), or a response time in frames and how much it may oscillate
// (slide 3:3:1). The effective mass the constraint sees is computed by the solver, so the
// same Spring behaves the same on a 1 g body and on a 1 t body.
//
// Or a spring is given in absolute units (Spring::absolute): a stiffness k (N/m, or N m/rad on
// an angle) and a damping c (N s/m, N m s/rad). The solver then converts with the effective
// mass of the row in each sub-step (K = 1/m_eff):
//   a = h (c + h k) K,  bias_rate = k / (c + h k),  mass_scale = a/(1+a),  impulse_scale = 1/(1+a)
// (the relative form is this with k = m_eff omega^2, c = 2 m_eff zeta omega). Such a spring
// behaves differently on a 1 g and a 1 t body, as a real one does: a car's suspension is tuned
// for the chassis it carries, not for the wheel that dominates the row's effective mass.
// k = 0 with c > 0 is a pure damper (bias_rate 0, a = h c K); k = c = 0 is a free spring.
// Which joints take absolute units: the one-row springs (revolute N m/rad, prismatic N/m,
// wheel suspension N/m, distance joint N/m). The others (ball, weld, swing-twist, motor
// joint) reject them naming the field (".units"): their springs are 3-row blocks with a
// 3x3 K, whose conversion is not done.
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

// Which of a Spring's fields hold it: hertz and damping_ratio (relative to the effective mass
// the solver computes), or absolute_stiffness and absolute_damping.
enum class SpringUnits : unsigned char { Relative, Absolute };

struct Spring {
  // Oscillation frequency, Hz. +infinity: rigid. 0: no spring at all (free).
  double hertz = std::numeric_limits<double>::infinity();
  // Damping ratio zeta, dimensionless: 0 undamped, 1 critically damped, > 1 overdamped.
  double damping_ratio = 0.0;
  SpringUnits units = SpringUnits::Relative;
  // Absolute units only (hertz and damping_ratio are then 0): k in N/m or N m/rad, c in
  // N s/m or N m s/rad, each 0 or in [1e-6, 1e9].
  double absolute_stiffness = 0.0;
  double absolute_damping = 0.0;

  static Spring rigid() { return {}; }
  static Spring free() { return {0.0, 0.0}; }
  static Spring soft(double hertz, double damping_ratio) { return {hertz, damping_ratio}; }
  // A spring in absolute units (see the top): stiffness k and damping c, kept as given (the
  // joint that takes it checks them: each 0 or in [1e-6, 1e9], naming the field).
  static Spring absolute(double stiffness, double damping) {
    return {0.0, 0.0, SpringUnits::Absolute, stiffness, damping};
  }
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

  bool is_absolute() const { return units == SpringUnits::Absolute; }
  bool is_rigid() const {
    return !is_absolute() && hertz == std::numeric_limits<double>::infinity();
  }
  bool is_free() const {
    return is_absolute() ? absolute_stiffness == 0.0 && absolute_damping == 0.0 : hertz == 0.0;
  }

  // k = m omega^2, N/m (absolute units: absolute_stiffness, whatever the mass)
  double stiffness(double effective_mass) const;
  // c = 2 m zeta omega, N s/m (absolute units: absolute_damping)
  double damping(double effective_mass) const;
  // gamma/beta (= CFM/ERP) and the solver's coefficients for step h as seen by an effective
  // mass. A rigid spring gives gamma = 0, beta = 1.
  SoftCoefficients coefficients(double effective_mass, double h) const;
};

}  // namespace softstep
