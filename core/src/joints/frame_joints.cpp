// What the angular kinds share on the core side (frame_joints.hpp).
#include "joints/frame_joints.hpp"

#include <cmath>
#include <numbers>

#include "state_hasher.hpp"

namespace softstep {

Quaternion frame_rotation(const JointFrame& frame) {
  const Eigen::Vector3d z = frame.local_axis.normalized();
  const Eigen::Vector3d x = (frame.local_reference - frame.local_reference.dot(z) * z).normalized();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return Quaternion(r).normalized();
}

JointFrame checked_frame(std::string_view call, const std::string& field, const JointFrame& frame) {
  validation::finite(call, field + ".local_anchor", frame.local_anchor);
  validation::finite(call, field + ".local_axis", frame.local_axis);
  validation::finite(call, field + ".local_reference", frame.local_reference);
  const double axis_length = frame.local_axis.norm();
  if (!(axis_length > 1e-9) || axis_length > validation::kMaxMagnitude) {
    validation::reject(call, field + ".local_axis", validation::format(frame.local_axis),
                       "must have a length in (1e-9, 1e9] (it is normalized)");
  }
  JointFrame out = frame;
  out.local_axis = frame.local_axis / axis_length;
  const double reference_length = frame.local_reference.norm();
  const Eigen::Vector3d perpendicular =
      frame.local_reference - frame.local_reference.dot(out.local_axis) * out.local_axis;
  if (!(reference_length > 1e-9) || reference_length > validation::kMaxMagnitude ||
      !(perpendicular.norm() > 1e-6 * reference_length)) {
    validation::reject(call, field + ".local_reference", validation::format(frame.local_reference),
                       "must be a non-zero direction not parallel to the axis");
  }
  out.local_reference = perpendicular.normalized();
  return out;
}

JointSlot checked_frame_ends(const World::Impl& w, std::string_view call, std::string_view def,
                             BodyId a, BodyId b, JointFrame& frame_a, JointFrame& frame_b) {
  JointSlot j = checked_joint_ends(w, call, def, a, b, frame_a.local_anchor, frame_b.local_anchor,
                                   PointRows::Yes, "frame_a.local_anchor", "frame_b.local_anchor");
  const std::string prefix(def);
  frame_a = checked_frame(call, prefix + ".frame_a", frame_a);
  frame_b = checked_frame(call, prefix + ".frame_b", frame_b);
  return j;
}

WorldFrames world_frames(const BodySlot& a, const BodySlot& b, const JointFrame& frame_a,
                         const JointFrame& frame_b) {
  return {(a.orientation * frame_rotation(frame_a)).normalized(),
          (b.orientation * frame_rotation(frame_b)).normalized()};
}

WorldFrames world_frames(const World::Impl& w, const JointSlot& j, const JointFrame& frame_a,
                         const JointFrame& frame_b) {
  return world_frames(w.bodies[j.body_a], w.bodies[j.body_b], frame_a, frame_b);
}

double wrapped_hinge_angle(const WorldFrames& f) {
  const Quaternion q = f.a.conjugate() * f.b;
  double angle = 2.0 * std::atan2(q.z(), q.w());  // (-2 pi, 2 pi]
  if (angle > std::numbers::pi) angle -= 2.0 * std::numbers::pi;
  if (angle <= -std::numbers::pi) angle += 2.0 * std::numbers::pi;
  return angle;
}

double unwrap_angle(double previous, double wrapped) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double turns = std::round((previous - wrapped) / kTwoPi);
  return wrapped + turns * kTwoPi;
}

void check_axis_limit(std::string_view call, const std::string& field, const AxisLimit& limit) {
  validation::finite(call, field + ".lower", limit.lower);
  validation::finite(call, field + ".upper", limit.upper);
  for (const auto& [name, value] : {std::pair{".lower", limit.lower}, {".upper", limit.upper}}) {
    if (std::abs(value) > validation::kMaxMagnitude) {
      validation::reject(call, field + name, validation::format(value),
                         "must lie within +-" + validation::format(validation::kMaxMagnitude));
    }
  }
  if (limit.lower > limit.upper) {
    validation::reject(call, field + ".lower", validation::format(limit.lower),
                       "must be <= upper (" + validation::format(limit.upper) + ")");
  }
}

void check_motor(std::string_view call, const std::string& field, double speed, double max,
                 const char* max_name) {
  validation::finite(call, field + ".speed", speed);
  if (std::abs(speed) > validation::kMaxMagnitude) {
    validation::reject(call, field + ".speed", validation::format(speed),
                       "must lie within +-" + validation::format(validation::kMaxMagnitude));
  }
  validation::non_negative(call, field + "." + max_name, max);
  if (max > validation::kMaxMagnitude) {
    validation::reject(call, field + "." + max_name, validation::format(max),
                       "must be <= " + validation::format(validation::kMaxMagnitude));
  }
}

void check_axis_spring(std::string_view call, const std::string& field, const AxisSpring& spring) {
  validation::spring(call, field + ".spring", spring.spring);
  if (spring.spring.is_rigid()) {
    validation::reject(call, field + ".spring.hertz", "inf",
                       "an axis spring is soft or free (lock the axis with a limit instead)");
  }
  validation::finite(call, field + ".target", spring.target);
  if (std::abs(spring.target) > validation::kMaxMagnitude) {
    validation::reject(call, field + ".target", validation::format(spring.target),
                       "must lie within +-" + validation::format(validation::kMaxMagnitude));
  }
}

std::uint32_t axis_signature(const AxisLimit& limit, bool motor, const AxisSpring& spring) {
  return (limit.enabled ? simd::kAxisLimit : 0u) | (motor ? simd::kAxisMotor : 0u) |
         (spring.spring.is_free() ? 0u : simd::kAxisSpring);
}

int axis_control_rows(std::uint32_t s) {
  return ((s & simd::kAxisLimit) ? 2 : 0) + ((s & simd::kAxisMotor) ? 1 : 0) +
         ((s & simd::kAxisSpring) ? 1 : 0);
}

std::string axis_parts(std::uint32_t signature) {
  std::string s;
  if (signature & simd::kAxisSpring) s += " + spring";
  if (signature & simd::kAxisMotor) s += " + motor";
  if (signature & simd::kAxisLimit) s += " + limits";
  return s;
}

double slider_effective_mass(const World::Impl& w, const JointSlot& j, const WorldAnchors& anchors,
                             const Eigen::Vector3d& axis) {
  const BodySlot& a = w.bodies[j.body_a];
  const BodySlot& b = w.bodies[j.body_b];
  return linear_effective_mass(a, b, anchors.b - a.position, anchors.b - b.position, axis);
}

double read_axis_controls(const float* impulse, JointReading& r) {
  r.limit_impulse = double(impulse[kAxisImpulses]) - double(impulse[kAxisImpulses + 1]);
  r.motor_impulse = impulse[kAxisImpulses + 2];
  r.spring_impulse = impulse[kAxisImpulses + 3];
  return r.limit_impulse + r.motor_impulse + r.spring_impulse;
}

void hash_axis_controls(StateHasher& h, const AxisLimit& limit, bool motor_enabled,
                        double motor_speed, double motor_max, const AxisSpring& spring) {
  h.value(limit.enabled);
  h.value(limit.lower);
  h.value(limit.upper);
  h.value(motor_enabled);
  h.value(motor_speed);
  h.value(motor_max);
  hash_spring(h, spring.spring);
  h.value(spring.target);
}

void hash_frame(StateHasher& h, const JointFrame& f) {
  h.matrix(f.local_anchor);
  h.matrix(f.local_axis);
  h.matrix(f.local_reference);
}

namespace {
JointFrames local_frames(const World& world, BodyId a, BodyId b,
                         const Eigen::Vector3d& world_anchor, const Eigen::Vector3d& axis,
                         const Eigen::Vector3d& reference) {
  const auto local = [&](const BodyState& s) {
    const Quaternion inverse = s.orientation.conjugate();
    return JointFrame{inverse * (world_anchor - s.position), inverse * axis, inverse * reference};
  };
  return {local(world.body(a)), local(world.body(b))};
}

Eigen::Vector3d checked_world_axis(const Eigen::Vector3d& world_anchor,
                                   const Eigen::Vector3d& world_axis) {
  validation::finite("frames_at", "world_anchor", world_anchor);
  validation::finite("frames_at", "world_axis", world_axis);
  if (!(world_axis.norm() > 1e-9)) {
    validation::reject("frames_at", "world_axis", validation::format(world_axis),
                       "must not be zero");
  }
  return world_axis.normalized();
}
}  // namespace

JointFrames frames_at(const World& world, BodyId a, BodyId b, const Eigen::Vector3d& world_anchor,
                      const Eigen::Vector3d& world_axis) {
  world.body(a);  // unknown bodies are rejected first
  world.body(b);
  const Eigen::Vector3d axis = checked_world_axis(world_anchor, world_axis);
  // A reference perpendicular to the axis: the world axis least aligned with it, made
  // perpendicular.
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d reference =
      (Eigen::Vector3d::Unit(least) - axis[least] * axis).normalized();
  return local_frames(world, a, b, world_anchor, axis, reference);
}

JointFrames frames_at(const World& world, BodyId a, BodyId b, const Eigen::Vector3d& world_anchor,
                      const Eigen::Vector3d& world_axis, const Eigen::Vector3d& world_reference) {
  world.body(a);
  world.body(b);
  const Eigen::Vector3d axis = checked_world_axis(world_anchor, world_axis);
  validation::finite("frames_at", "world_reference", world_reference);
  const Eigen::Vector3d perpendicular = world_reference - world_reference.dot(axis) * axis;
  if (!(perpendicular.norm() > 1e-6 * world_reference.norm()) || !(world_reference.norm() > 1e-9)) {
    validation::reject("frames_at", "world_reference", validation::format(world_reference),
                       "must be a non-zero direction not parallel to the axis");
  }
  return local_frames(world, a, b, world_anchor, axis, perpendicular.normalized());
}

}  // namespace softstep
