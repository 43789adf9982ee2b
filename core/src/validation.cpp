#include "validation.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

namespace softstep::validation {

// The float envelope. The solver works in float (max 3.4e38) on products of these values:
// an effective mass times a speed (1e15 kg x 1e6 m/s), an anchor offset squared over an
// inertia (1e9 m squared / 1e-15 kg m^2), a position error over a sub-step (2e9 m / 1e-9 s)
// times a mass. Each bound keeps every such product below ~1e34, with room for the sums a
// Gauss-Seidel pass adds; a value beyond them is rejected here rather than left to become inf
// in a kernel. (The fuzzer found a world of 1e18 kg, 1e18 m/s and dt 68 s, each accepted
// under the earlier +-1e18 bound, whose products turned a body NaN.)
constexpr double kMinInertia = 1e-15;  // kg m^2
constexpr double kMaxInertia = 1e24;
// The largest principal moment over the smallest. The solver holds the world-frame inverse
// tensor in float (7 digits), where a tensor conditioned worse can round to an indefinite one;
// and a double eigenvalue below ~1e-16 of the largest is rounding noise. (The fuzzer found a
// singular tensor, [a a a; a a a; a a 1e12], accepted because its computed smallest eigenvalue
// was noise, 3e-5 > 0; its inverse was infinite and the body turned NaN at its first joint.)
// Up to 1e6 a locking joint holds such a body only because the kernels invert an
// ill-conditioned K by an LDL^T factorization (ldl_inverse_or_zero, math3.hpp): by float
// cofactors alone, a weld or prismatic on a body of moments 6e5 or more apart, its tensor
// turned from the world axes, let it fly hundreds of metres off its anchor in half of 20
// random orientations (|K K^-1 - 1| reached 16; Validation.EveryAcceptedInertiaRatioIsHeld-
// ByALockingJoint). That is a body held at rest: one a locking joint turns back from far off
// flies from 2e5 up at the default sub-step (1e4 at one sub-step per 1/60 s step; README,
// "Input ranges"), which this bound does not refuse: such bodies are sound inputs that the
// solver holds where they do not turn fast.
constexpr double kMaxInertiaRatio = 1e6;

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
  if (std::abs(value) > kMaxMagnitude)
    reject(call, field, format(value), "must be within +-" + format(kMaxMagnitude));
}

void finite(std::string_view call, std::string_view field, const Eigen::Vector3d& value) {
  if (!value.allFinite()) reject(call, field, format(value), "every component must be finite");
  if (value.cwiseAbs().maxCoeff() > kMaxMagnitude) {
    reject(call, field, format(value), "every component must be within +-" + format(kMaxMagnitude));
  }
}

void non_negative(std::string_view call, std::string_view field, double value) {
  if (!(std::isfinite(value) && value >= 0.0 && value <= kMaxMagnitude)) {
    reject(call, field, format(value), "must be finite, >= 0 and <= " + format(kMaxMagnitude));
  }
}

void positive(std::string_view call, std::string_view field, double value) {
  if (!(std::isfinite(value) && value >= kMinPositive && value <= kMaxMagnitude)) {
    reject(call, field, format(value),
           "must be in [" + format(kMinPositive) + ", " + format(kMaxMagnitude) + "]");
  }
}

Quaternion unit_quaternion(std::string_view call, std::string_view field, const Quaternion& q) {
  const Eigen::Vector4d c = q.coeffs();
  // Formatted only for a rejection: a create_body that passes formats nothing (issue 17).
  const auto value = [&] {
    return "(x " + format(c.x()) + ", y " + format(c.y()) + ", z " + format(c.z()) + ", w " +
           format(c.w()) + ")";
  };
  if (!c.allFinite()) reject(call, field, value(), "every component must be finite");
  if (std::abs(c.norm() - 1.0) > 1e-3) {
    reject(call, field, value(), "must be a unit quaternion (norm " + format(c.norm()) + ")");
  }
  return q.normalized();
}

void dynamic_mass(std::string_view call, std::string_view field, double mass) {
  if (!(std::isfinite(mass) && mass >= kMinMass && mass <= kMaxMass)) {
    reject(call, field, format(mass),
           "a dynamic body needs a finite mass in [" + format(kMinMass) + ", " + format(kMaxMass) +
               "] kg");
  }
}

void inertia_tensor(std::string_view call, std::string_view field, const Eigen::Matrix3d& inertia) {
  const auto value = [&] { return format(inertia); };
  if (!inertia.allFinite()) reject(call, field, value(), "every entry must be finite");
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    reject(call, field, value(), "must be symmetric");
  }
  // A diagonal tensor (the common case: principal axes as body axes) has its diagonal as its
  // eigenvalues. A full one takes the closed form (0.05 us) when its verdict is clear: well
  // inside the bounds and well conditioned, where its rounding cannot matter; otherwise the
  // iterative eigensolver (0.4 us) decides.
  Eigen::Vector3d eigenvalues = inertia.diagonal();
  if (!inertia.isDiagonal(0.0)) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(inertia, Eigen::EigenvaluesOnly);
    eigenvalues = solver.eigenvalues();
    const double low = eigenvalues.minCoeff(), high = eigenvalues.maxCoeff();
    const bool clear = std::isfinite(low) && std::isfinite(high) && low >= 2.0 * kMinInertia &&
                       high <= 0.5 * kMaxInertia && high <= 0.5 * kMaxInertiaRatio * low;
    if (!clear) {
      eigenvalues = solver.compute(inertia, Eigen::EigenvaluesOnly).eigenvalues();
    }
  }
  const double smallest = eigenvalues.minCoeff();
  if (!(smallest > 0.0) || smallest < kMinInertia || eigenvalues.maxCoeff() > kMaxInertia) {
    reject(call, field, value(),
           "must be positive definite with eigenvalues in [" + format(kMinInertia) + ", " +
               format(kMaxInertia) + "] kg m^2 (smallest " + format(smallest) + ", largest " +
               format(eigenvalues.maxCoeff()) + ")");
  }
  if (eigenvalues.maxCoeff() > kMaxInertiaRatio * smallest) {
    reject(call, field, value(),
           "principal moments more than " + format(kMaxInertiaRatio) +
               " apart cannot be solved in float (smallest " + format(smallest) + ", largest " +
               format(eigenvalues.maxCoeff()) + " kg m^2)");
  }
}

// The solver holds a point block's K = 1/m + [r]x^T I^-1 [r]x in float: its smallest
// eigenvalue, 1/m along r, drowns in the rounding of the largest, |r|^2 / I_min, once their
// ratio nears 1/epsilon, even factored by LDL^T (math3.hpp). A 1 kg bob on a rigid ball joint
// 100 m from its centre (a pendulum of a point anchor), released from 0.5 rad, fell through
// the joint, holding nothing, from m r^2 / I = 7e7 (and at 2.5e8, a 1 cm ball); from 1, 10 or
// 100 m and 0.1-1.5 rad it held in every set-up up to 1e6, and above that a 100 m pendulum
// released near horizontal opened by its length (the alignment mode of a tiny inertia under
// tension takes over there: README, "Hard cases"). So 1e7 refuses the joints that cannot hold
// and keeps the ones that can at more sub-steps (the "tiny inertia" hard case, 3.9e6). A
// corner sampler's worlds of this kind (a 1e15 kg body of inertia 1, an anchor 1e9 m out)
// were two thirds of its non-finite ones.
void point_lever(std::string_view call, std::string_view field, const std::string& shown,
                 const Eigen::Vector3d& anchor, double mass, const Eigen::Matrix3d& inertia) {
  double smallest = inertia.diagonal().minCoeff();
  if (!inertia.isDiagonal(0.0)) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    smallest = solver.compute(inertia, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  }
  const double condition = mass * anchor.squaredNorm() / smallest;
  if (condition > kMaxLeverCondition) {
    reject(call, field, shown,
           "puts a joint's anchor " + format(anchor) + " m from the centre of a body of mass " +
               format(mass) + " kg and smallest principal moment " + format(smallest) +
               " kg m^2: m |r|^2 / I_min = " + format(condition) + " > " +
               format(kMaxLeverCondition) +
               ", beyond what float point rows hold (a distance joint to the body's centre has "
               "no such limit; or give the body the inertia its lever needs)");
  }
}

std::string format(const Eigen::Matrix3d& inertia) {
  std::string text = "[";
  for (int i = 0; i < 9; ++i) text += format(inertia(i / 3, i % 3)) + (i == 8 ? "]" : " ");
  return text;
}

void spring(std::string_view call, std::string_view field, const Spring& s) {
  if (s.units != SpringUnits::Relative && s.units != SpringUnits::Absolute) {
    reject(call, std::string(field) + ".units", std::to_string(static_cast<int>(s.units)),
           "must be SpringUnits::Relative or SpringUnits::Absolute");
  }
  if (s.is_absolute()) {
    // The same bounds as every other magnitude: c + h k and a stay finite in float, and so
    // does 1 / (h (c + h k)): a positive k or c below kMinPositive overflowed it (1e-40 N/m
    // turned revolute, prismatic, wheel and distance joints' bodies NaN in the first step).
    for (const auto& [name, value] : {std::pair{".absolute_stiffness", s.absolute_stiffness},
                                      std::pair{".absolute_damping", s.absolute_damping}}) {
      if (!(std::isfinite(value) && (value == 0.0 || value >= kMinPositive) &&
            value <= kMaxMagnitude)) {
        reject(call, std::string(field) + name, format(value),
               "must be 0 or in [" + format(kMinPositive) + ", " + format(kMaxMagnitude) + "]");
      }
    }
    if (s.hertz != 0.0 || s.damping_ratio != 0.0) {
      reject(call, std::string(field) + ".hertz", format(s.hertz),
             "must be 0 with damping_ratio 0 in absolute units (Spring::absolute)");
    }
    return;
  }
  if (s.absolute_stiffness != 0.0 || s.absolute_damping != 0.0) {
    reject(call, std::string(field) + ".absolute_stiffness", format(s.absolute_stiffness),
           "must be 0 with absolute_damping 0 in relative units (hertz, damping_ratio); use "
           "Spring::absolute for a stiffness and damping");
  }
  // A positive frequency below kMinPositive would overflow the softness's 1/a in float.
  if (std::isnan(s.hertz) || s.hertz < 0.0 || (s.hertz > 0.0 && s.hertz < kMinPositive) ||
      (s.hertz > kMaxMagnitude && !s.is_rigid())) {
    reject(call, std::string(field) + ".hertz", format(s.hertz),
           "must be 0 (free), in [" + format(kMinPositive) + ", " + format(kMaxMagnitude) +
               "], or +infinity (rigid)");
  }
  if (!(std::isfinite(s.damping_ratio) && s.damping_ratio >= 0.0 &&
        s.damping_ratio <= kMaxMagnitude)) {
    non_negative(call, std::string(field) + ".damping_ratio", s.damping_ratio);
  }
}

void relative_spring(std::string_view call, std::string_view field, const Spring& s) {
  spring(call, field, s);
  if (s.is_absolute()) {
    reject(call, std::string(field) + ".units", "Absolute",
           "absolute units (N/m, N m/rad) are taken by the revolute, prismatic, wheel and "
           "distance joints' springs; give this spring as hertz and damping_ratio");
  }
}

void linear_speed(std::string_view call, std::string_view field, const Eigen::Vector3d& shown,
                  const Eigen::Vector3d& velocity, double max_speed) {
  if (!(velocity.norm() <= max_speed)) {
    reject(call, field, format(shown),
           "the speed " + format(velocity.norm()) +
               " m/s is beyond WorldSettings.max_linear_speed (" + format(max_speed) + " m/s)");
  }
}

void body_def(std::string_view call, const BodyDef& def, double max_linear_speed) {
  if (def.type != BodyType::Static && def.type != BodyType::Kinematic &&
      def.type != BodyType::Dynamic) {
    reject(call, "BodyDef.type", format(static_cast<double>(def.type)), "unknown body type");
  }
  finite(call, "BodyDef.position", def.position);
  unit_quaternion(call, "BodyDef.orientation", def.orientation);
  finite(call, "BodyDef.linear_velocity", def.linear_velocity);
  linear_speed(call, "BodyDef.linear_velocity", def.linear_velocity, def.linear_velocity,
               max_linear_speed);
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
  if (s.solver != SolverMode::Iterative && s.solver != SolverMode::DirectForTrees &&
      s.solver != SolverMode::Auto) {
    reject(call, "WorldSettings.solver", std::to_string(static_cast<int>(s.solver)),
           "must be SolverMode::Iterative, DirectForTrees or Auto");
  }
  if (!(s.max_linear_speed >= kMinPositive && s.max_linear_speed <= kMaxSpeedLimit)) {
    reject(call, "WorldSettings.max_linear_speed", format(s.max_linear_speed),
           "must be in [" + format(kMinPositive) + ", " + format(kMaxSpeedLimit) + "] m/s");
  }
  if (!(s.max_rotation_per_substep >= kMinPositive &&
        s.max_rotation_per_substep <= 0.5 * std::numbers::pi)) {
    reject(call, "WorldSettings.max_rotation_per_substep", format(s.max_rotation_per_substep),
           "must be in [" + format(kMinPositive) + ", " + format(0.5 * std::numbers::pi) +
               "] rad (a quarter turn)");
  }
  non_negative(call, "WorldSettings.rigid_damping_ratio", s.rigid_damping_ratio);
  positive(call, "WorldSettings.contact.hertz", s.contact.hertz);
  non_negative(call, "WorldSettings.contact.damping_ratio", s.contact.damping_ratio);
  positive(call, "WorldSettings.contact.max_push_out_speed", s.contact.max_push_out_speed);
  non_negative(call, "WorldSettings.contact.restitution_threshold",
               s.contact.restitution_threshold);
  positive(call, "WorldSettings.max_correction_speed", s.max_correction_speed);
  non_negative(call, "WorldSettings.sleep_linear_speed", s.sleep_linear_speed);
  non_negative(call, "WorldSettings.sleep_angular_speed", s.sleep_angular_speed);
  non_negative(call, "WorldSettings.time_to_sleep", s.time_to_sleep);
}

}  // namespace softstep::validation
