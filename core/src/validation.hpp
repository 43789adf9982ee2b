// Checks for the public API. Each throws InvalidArgument naming the call, the field and the
// value; none changes anything, so a caller that validates first leaves the world untouched.
// Messages are formatted only once a check has failed: formatting them up front made
// create_body cost 8-9 us (issue 17).
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "softstep/body.hpp"
#include "softstep/errors.hpp"
#include "softstep/joints.hpp"
#include "softstep/world_settings.hpp"

namespace softstep::validation {

// Bounds of the float envelope (validation.cpp explains them): every position, length,
// anchor, gravity, frequency and other plain magnitude lies within +-kMaxMagnitude.
inline constexpr double kMaxMagnitude = 1e9;
// The smallest positive frequency or speed: below it float's 1/(h omega)^2 terms overflow.
inline constexpr double kMinPositive = 1e-6;
inline constexpr double kMaxSpeedLimit = 1e6;  // m/s, the largest max_linear_speed
inline constexpr double kMinMass = 1e-9;       // kg, a dynamic body's (and a wheel's sprung mass)
inline constexpr double kMaxMass = 1e15;
inline constexpr double kMinSubstep = 1e-9;    // s
inline constexpr double kMaxSubstep = 1e3;     // s

std::string format(double value);
std::string format(const Eigen::Vector3d& value);

[[noreturn]] void reject(std::string_view call, std::string_view field, const std::string& value,
                         std::string_view rule);

// What finite() accepts: finite and within +-kMaxMagnitude (every component). For checks that
// test first and name the field only on failure (contact_validation.cpp).
// Inline and without branches: the contact checks test every point's anchors each step. A NaN
// fails the comparison, an infinity the bound, so no separate finiteness test is needed.
inline bool in_envelope(double value) {
  return std::abs(value) <= kMaxMagnitude;
}
inline bool in_envelope(const Eigen::Vector3d& value) {
  bool inside = in_envelope(value.x());
  inside &= in_envelope(value.y());
  inside &= in_envelope(value.z());
  return inside;
}
void finite(std::string_view call, std::string_view field, double value);
void finite(std::string_view call, std::string_view field, const Eigen::Vector3d& value);
void non_negative(std::string_view call, std::string_view field, double value);
void positive(std::string_view call, std::string_view field, double value);
// Normalizes a quaternion whose norm is within 1e-3 of 1; rejects anything else.
Quaternion unit_quaternion(std::string_view call, std::string_view field, const Quaternion& q);
void dynamic_mass(std::string_view call, std::string_view field, double mass);
void inertia_tensor(std::string_view call, std::string_view field, const Eigen::Matrix3d& inertia);
// A joint's point rows (every joint but the distance joint: ball, and the point or lateral
// rows of the frame joints) on a dynamic body of this mass and inertia, anchored `anchor` from
// its centre (body frame). Their 3x3 effective mass has a condition of about
// m |anchor|^2 / I_min (I_min the smallest principal moment): beyond kMaxLeverCondition the
// float solver cannot hold the joint, and `field` is refused showing `shown` (the anchor, or
// the inertia that set_mass_properties would give the body).
inline constexpr double kMaxLeverCondition = 1e7;
void point_lever(std::string_view call, std::string_view field, const std::string& shown,
                 const Eigen::Vector3d& anchor, double mass, const Eigen::Matrix3d& inertia);
// An inertia tensor as the messages show it: [xx xy xz yx ...].
std::string format(const Eigen::Matrix3d& inertia);
void spring(std::string_view call, std::string_view field, const Spring& spring);
// spring() for the joints whose springs take only hertz and damping_ratio (Spring::absolute
// is rejected naming the field and the joints that take it).
void relative_spring(std::string_view call, std::string_view field, const Spring& spring);
// |velocity| <= max_speed (WorldSettings.max_linear_speed), after finite(). `shown` is what
// the caller was given (the velocity itself, or the impulse that would give it), formatted
// only when the check fails.
void linear_speed(std::string_view call, std::string_view field, const Eigen::Vector3d& shown,
                  const Eigen::Vector3d& velocity, double max_speed);
void body_def(std::string_view call, const BodyDef& def, double max_linear_speed);
void settings(std::string_view call, const WorldSettings& settings);

}  // namespace softstep::validation
