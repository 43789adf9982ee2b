#include "softstep/analytic.hpp"

#include <cmath>

namespace softstep::analytic {

double implicit_euler_spring_velocity(double x1, double v1, double mass, double k, double c,
                                      double h) {
  return (v1 - h * k / mass * x1) / (1.0 + h * c / mass + h * h * k / mass);
}

double harmonic_oscillator_position(double x0, double v0, double omega, double zeta, double t) {
  if (zeta < 1.0) {  // under-damped: a decaying cosine
    const double wd = omega * std::sqrt(1.0 - zeta * zeta);
    const double decay = std::exp(-zeta * omega * t);
    return decay * (x0 * std::cos(wd * t) + (v0 + zeta * omega * x0) / wd * std::sin(wd * t));
  }
  if (zeta == 1.0) {  // critically damped
    return std::exp(-omega * t) * (x0 + (v0 + omega * x0) * t);
  }
  // over-damped: two real decays r1, r2 < 0
  const double root = omega * std::sqrt(zeta * zeta - 1.0);
  const double r1 = -zeta * omega + root;
  const double r2 = -zeta * omega - root;
  const double b = (v0 - r1 * x0) / (r2 - r1);
  return (x0 - b) * std::exp(r1 * t) + b * std::exp(r2 * t);
}

double small_angle_pendulum_frequency(double mass, double distance, double inertia_about_centre,
                                      double g) {
  return std::sqrt(mass * g * distance / (inertia_about_centre + mass * distance * distance));
}

double small_angle_pendulum_angle(double theta0, double omega, double t) {
  return theta0 * std::cos(omega * t);
}

std::vector<double> hanging_chain_tension(std::span<const double> link_masses, double g) {
  std::vector<double> tension(link_masses.size());
  double below = 0.0;
  for (std::size_t i = link_masses.size(); i-- > 0;) {
    below += link_masses[i];
    tension[i] = below * g;
  }
  return tension;
}

}  // namespace softstep::analytic
