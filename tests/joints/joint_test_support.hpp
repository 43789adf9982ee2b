// Small helpers the joint tests share: a world with a static ground, a box body, and the
// frequency of a signal from its zero crossings.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "frame_constants.hpp"
#include "softstep/softstep.hpp"

namespace softstep::test {

// The same inertia turned by `rotation` in the body frame: products of inertia, so the
// body's principal axes are not the joint's (a body hinged off its principal axes needs the
// joint's off-axis torques to keep turning about the hinge).
inline Eigen::Matrix3d turned(const Eigen::Matrix3d& inertia, const Eigen::Matrix3d& rotation) {
  return rotation * inertia * rotation.transpose();
}

// A rigid row is solved as a spring of rigid_hertz (60 Hz, capped at 1/(4 h): 60 Hz at 4
// sub-steps of 1/60 s) and relaxed without bias. Carrying a steady load L on its effective
// mass m_eff (alpha = L / m_eff) it sags alpha / omega_r^2; a one-sided limit row,
// speculative while inside, lets through at most one sub-step's acceleration, alpha h^2,
// before it acts. The bound takes twice the sum, for the Gauss-Seidel coupling with the
// joint's other rows. An angular row's m_eff is the inertia about the body's centre along
// the axis (1 / (a . I^-1 a) with A static), not about the joint.
inline constexpr double kOmegaRigid = 2.0 * std::numbers::pi * 60.0;
inline double rigid_row_bound(double alpha, double h) {
  return 2.0 * (alpha * h * h + alpha / (kOmegaRigid * kOmegaRigid));
}

inline BodyId static_body(World& world, const Eigen::Vector3d& position = Eigen::Vector3d::Zero()) {
  BodyDef d;
  d.type = BodyType::Static;
  d.position = position;
  return world.create_body(d);
}

inline BodyId dynamic_body(World& world, const Eigen::Vector3d& position, double mass,
                           const Eigen::Matrix3d& inertia,
                           const Quaternion& orientation = Quaternion::Identity()) {
  BodyDef d;
  d.position = position;
  d.orientation = orientation;
  d.mass = mass;
  d.inertia = inertia;
  return world.create_body(d);
}

// Times (s) at which `sample` crosses zero going upwards, interpolated linearly inside the
// step, while `advance` steps the world `steps` times by dt.
inline std::vector<double> upward_crossings(const std::function<void()>& advance,
                                            const std::function<double()>& sample, double dt,
                                            int steps) {
  std::vector<double> crossings;
  double previous = sample();
  for (int i = 1; i <= steps; ++i) {
    advance();
    const double now = sample();
    if (previous < 0.0 && now >= 0.0)
      crossings.push_back((i - 1 + previous / (previous - now)) * dt);
    previous = now;
  }
  return crossings;
}

// Mean period between the first and the last crossing; 0 when fewer than two.
inline double mean_period(const std::vector<double>& crossings) {
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

// The rotation angle of q about `axis` (unit), rad in (-pi, pi]: the twist part of q.
inline double twist_angle(const Quaternion& q, const Eigen::Vector3d& axis) {
  const double along = q.vec().dot(axis);
  return 2.0 * std::atan2(along, q.w());
}

}  // namespace softstep::test
