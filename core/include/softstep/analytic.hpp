// Closed-form solutions the accuracy references are checked against (talk part 1 and 2).
#pragma once

#include <span>
#include <vector>

namespace softstep::analytic {

// Talk 2:3:1: one implicit-Euler step h of a mass m on a spring k (N/m) and damper c (N s/m)
// to the ground, from position x1 and velocity v1: the new velocity
//   v2 = (v1 - h k/m x1) / (1 + h c/m + h^2 k/m)
// which a soft constraint under semi-implicit Euler reproduces exactly (talk 2:3:2).
double implicit_euler_spring_velocity(double x1, double v1, double mass, double k, double c,
                                      double h);

// Talk 1:1: the exact motion of the harmonic oscillator x'' + 2 zeta omega x' + omega^2 x = 0
// from x(0) = x0, x'(0) = v0 (any zeta >= 0): x(t), m.
double harmonic_oscillator_position(double x0, double v0, double omega, double zeta, double t);

// A rigid body swinging about a fixed pivot at distance d from its centre of mass, with
// moment of inertia inertia_about_centre (kg m^2): small oscillations have angular frequency
// sqrt(m g d / (I + m d^2)), rad/s, and theta(t) = theta0 cos(omega t) from rest.
double small_angle_pendulum_frequency(double mass, double distance, double inertia_about_centre,
                                      double g);
double small_angle_pendulum_angle(double theta0, double omega, double t);

// A chain hanging at rest from a fixed anchor, links given top first: the tension in joint i
// (joint 0 holds link 0 to the anchor) is the weight of links i..n-1, N.
std::vector<double> hanging_chain_tension(std::span<const double> link_masses, double g);

}  // namespace softstep::analytic
