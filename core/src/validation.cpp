#include "validation.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

namespace softstep::validation {

// Masses outside this range have an inverse that float cannot hold (or that is denormal).
constexpr double kMinMass = 1e-30;
constexpr double kMaxMass = 1e30;
// The solver works in float (max 3.4e38) on products of these values; anything larger than
// this is rejected as out of range rather than left to turn into inf in a kernel.
constexpr double kMaxMagnitude = 1e18;

std::string format(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

std::string format(const Eigen::Vector3d& v) {
  return "(" + format(v.x()) + ", " + format(v.y()) + ", " + format(v.z()) + ")";
}

void reject(std::string_view call, std::string_view field, const std::string& value,
            std::string_view rule) {
  std::string message = "softstep: ";
  message.append(call).append(": ").append(field).append(" = ").append(value);
  message.append(" rejected: ").append(rule);
  throw InvalidArgument(std::string(field), message);
}

void finite(std::string_view call, std::string_view field, double value) {
  if (!std::isfinite(value)) reject(call, field, format(value), "must be finite");
  if (std::abs(value) > kMaxMagnitude) reject(call, field, format(value), "must be within +-1e18");
}

void finite(std::string_view call, std::string_view field, const Eigen::Vector3d& value) {
  if (!value.allFinite()) reject(call, field, format(value), "every component must be finite");
  if (value.cwiseAbs().maxCoeff() > kMaxMagnitude) {
    reject(call, field, format(value), "every component must be within +-1e18");
  }
}

void non_negative(std::string_view call, std::string_view field, double value) {
  if (!(std::isfinite(value) && value >= 0.0 && value <= kMaxMagnitude)) {
    reject(call, field, format(value), "must be finite, >= 0 and <= 1e18");
  }
}

void positive(std::string_view call, std::string_view field, double value) {
  if (!(std::isfinite(value) && value > 0.0 && value <= kMaxMagnitude)) {
    reject(call, field, format(value), "must be finite, > 0 and <= 1e18");
  }
}

Quaternion unit_quaternion(std::string_view call, std::string_view field, const Quaternion& q) {
  const Eigen::Vector4d c = q.coeffs();
  const std::string value = "(x " + format(c.x()) + ", y " + format(c.y()) + ", z " +
                            format(c.z()) + ", w " + format(c.w()) + ")";
  if (!c.allFinite()) reject(call, field, value, "every component must be finite");
  if (std::abs(c.norm() - 1.0) > 1e-3) {
    reject(call, field, value, "must be a unit quaternion (norm " + format(c.norm()) + ")");
  }
  return q.normalized();
}

void dynamic_mass(std::string_view call, std::string_view field, double mass) {
  if (!(std::isfinite(mass) && mass >= kMinMass && mass <= kMaxMass)) {
    reject(call, field, format(mass), "a dynamic body needs a finite mass in [1e-30, 1e30] kg");
  }
}

void inertia_tensor(std::string_view call, std::string_view field, const Eigen::Matrix3d& inertia) {
  std::string value = "[";
  for (int i = 0; i < 9; ++i) value += format(inertia(i / 3, i % 3)) + (i == 8 ? "]" : " ");
  if (!inertia.allFinite()) reject(call, field, value, "every entry must be finite");
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    reject(call, field, value, "must be symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues().minCoeff();
  if (!(smallest > 0.0) || smallest < kMinMass * 1e-6 ||
      eigen.eigenvalues().maxCoeff() > kMaxMass) {
    reject(call, field, value,
           "must be positive definite with eigenvalues in [1e-36, 1e30] kg m^2 (smallest " +
               format(smallest) + ")");
  }
}

void spring(std::string_view call, std::string_view field, const Spring& s) {
  const std::string hertz_field = std::string(field) + ".hertz";
  const std::string zeta_field = std::string(field) + ".damping_ratio";
  if (std::isnan(s.hertz) || s.hertz < 0.0 || (s.hertz > kMaxMagnitude && !s.is_rigid())) {
    reject(call, hertz_field, format(s.hertz),
           "must be in [0, 1e18] (0 = free) or +infinity (rigid)");
  }
  non_negative(call, zeta_field, s.damping_ratio);
}

void body_def(std::string_view call, const BodyDef& def) {
  if (def.type != BodyType::Static && def.type != BodyType::Kinematic &&
      def.type != BodyType::Dynamic) {
    reject(call, "BodyDef.type", format(static_cast<double>(def.type)), "unknown body type");
  }
  finite(call, "BodyDef.position", def.position);
  unit_quaternion(call, "BodyDef.orientation", def.orientation);
  finite(call, "BodyDef.linear_velocity", def.linear_velocity);
  finite(call, "BodyDef.angular_velocity", def.angular_velocity);
  if (def.type == BodyType::Static &&
      (!def.linear_velocity.isZero(0.0) || !def.angular_velocity.isZero(0.0))) {
    reject(call, "BodyDef.linear_velocity",
           format(def.linear_velocity) + ", angular " + format(def.angular_velocity),
           "a static body cannot move (use a kinematic body)");
  }
  if (def.type == BodyType::Dynamic) {
    dynamic_mass(call, "BodyDef.mass", def.mass);
    inertia_tensor(call, "BodyDef.inertia", def.inertia);
  }
  finite(call, "BodyDef.gravity_scale", def.gravity_scale);
  non_negative(call, "BodyDef.linear_damping", def.linear_damping);
  non_negative(call, "BodyDef.angular_damping", def.angular_damping);
}

void settings(std::string_view call, const WorldSettings& s) {
  finite(call, "WorldSettings.gravity", s.gravity);
  if (s.substeps < 1 || s.substeps > 1000) {
    reject(call, "WorldSettings.substeps", std::to_string(s.substeps), "must be in [1, 1000]");
  }
  if (s.solve_iterations < 1 || s.solve_iterations > 1000) {
    reject(call, "WorldSettings.solve_iterations", std::to_string(s.solve_iterations),
           "must be in [1, 1000]");
  }
  if (s.relax_iterations < 0 || s.relax_iterations > 1000) {
    reject(call, "WorldSettings.relax_iterations", std::to_string(s.relax_iterations),
           "must be in [0, 1000]");
  }
  if (s.threads < 0 || s.threads > 256) {
    reject(call, "WorldSettings.threads", std::to_string(s.threads),
           "must be in [0, 256] (0 = all of the machine's cores)");
  }
  positive(call, "WorldSettings.rigid_hertz", s.rigid_hertz);
  non_negative(call, "WorldSettings.rigid_damping_ratio", s.rigid_damping_ratio);
  positive(call, "WorldSettings.max_correction_speed", s.max_correction_speed);
  non_negative(call, "WorldSettings.sleep_linear_speed", s.sleep_linear_speed);
  non_negative(call, "WorldSettings.sleep_angular_speed", s.sleep_angular_speed);
  non_negative(call, "WorldSettings.time_to_sleep", s.time_to_sleep);
}

}  // namespace softstep::validation
