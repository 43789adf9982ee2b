#include "softstep/spring.hpp"

#include <cmath>
#include <numbers>

#include "validation.hpp"

namespace softstep {

namespace {
double omega_of(double hertz) {
  return 2.0 * std::numbers::pi * hertz;
}

// The helpers' arguments: a spring that is none of these (NaN, negative, a zero that makes
// the spring rigid or its damping NaN) is rejected rather than returned (issue 17).
void check_positive(const char* call, const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    validation::reject(call, field, validation::format(value), "must be finite and > 0");
  }
}
void check_non_negative(const char* call, const char* field, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    validation::reject(call, field, validation::format(value), "must be finite and >= 0");
  }
}
}  // namespace

Spring Spring::designer(double frames, Oscillation oscillation, double frame_rate) {
  const char* call = "Spring::designer";
  check_positive(call, "frames", frames);
  check_positive(call, "frame_rate", frame_rate);
  if (oscillation != Oscillation::Free && oscillation != Oscillation::Some &&
      oscillation != Oscillation::None) {
    validation::reject(call, "oscillation", std::to_string(static_cast<int>(oscillation)),
                       "must be Oscillation::Free, Some or None");
  }
  const double zeta = oscillation == Oscillation::Free   ? 0.0
                      : oscillation == Oscillation::Some ? 0.5
                                                         : 1.0;
  return {frame_rate / frames, zeta};
}

Spring Spring::from_stiffness(double k, double c, double effective_mass) {
  const char* call = "Spring::from_stiffness";
  check_non_negative(call, "k", k);
  check_non_negative(call, "c", c);
  check_positive(call, "effective_mass", effective_mass);
  if (k == 0.0) return free();
  const double omega = std::sqrt(k / effective_mass);
  return {omega / (2.0 * std::numbers::pi), c / (2.0 * effective_mass * omega)};
}

Spring Spring::from_erp_cfm(double erp, double cfm, double effective_mass, double h) {
  // Talk 2:3:2 inverted: CFM = gamma = 1/(c + h k) and ERP = beta = h k/(c + h k) give
  // h k = ERP / CFM and c = 1/CFM - h k.
  const char* call = "Spring::from_erp_cfm";
  if (!(erp >= 0.0 && erp <= 1.0)) {
    validation::reject(call, "erp", validation::format(erp), "must be in [0, 1]");
  }
  check_positive(call, "cfm", cfm);
  check_positive(call, "effective_mass", effective_mass);
  check_positive(call, "h", h);
  const double k = erp / (h * cfm);
  const double c = (1.0 - erp) / cfm;
  return from_stiffness(k, c, effective_mass);
}

double Spring::stiffness(double effective_mass) const {
  if (is_absolute()) return absolute_stiffness;
  const double omega = omega_of(hertz);
  return effective_mass * omega * omega;
}

double Spring::damping(double effective_mass) const {
  if (is_absolute()) return absolute_damping;
  return 2.0 * effective_mass * damping_ratio * omega_of(hertz);
}

SoftCoefficients Spring::coefficients(double effective_mass, double h) const {
  if (is_rigid()) return {0.0, 1.0, 1.0 / h, 1.0, 0.0};
  if (is_free()) return {std::numeric_limits<double>::infinity(), 0.0, 0.0, 0.0, 1.0};
  const double k = stiffness(effective_mass);
  const double c = damping(effective_mass);
  const double gamma = 1.0 / (c + h * k);
  const double beta = h * k / (c + h * k);
  if (is_absolute()) {
    // a = h (c + h k) K with K = 1/m_eff (the top of spring.hpp).
    const double a = h * (c + h * k) / effective_mass;
    return {gamma, beta, beta / h, a / (1.0 + a), 1.0 / (1.0 + a)};
  }
  const double omega = omega_of(hertz);
  const double a = h * omega * (2.0 * damping_ratio + h * omega);
  return {gamma, beta, beta / h, a / (1.0 + a), 1.0 / (1.0 + a)};
}

}  // namespace softstep
