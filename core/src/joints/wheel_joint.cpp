// The wheel joint: validation, lanes, reading (see wheel_joint.hpp and
// simd/wheel_joint_kernel.hpp).
#include "joints/wheel_joint.hpp"

#include <algorithm>
#include <cmath>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "state_hasher.hpp"

namespace softstep {

std::uint32_t WheelKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return axis_signature(d.limit, d.motor.enabled, d.spring);
}

int WheelKind::rows(std::size_t, std::uint32_t s) {
  return 4 + axis_control_rows(s);  // the lateral and axle locks, then the axis controls
}

PlanKernel WheelKind::plan_kernel(std::size_t, std::uint32_t s) {
  PlanKernel k{};
  k.type = type;
  k.row = SpringRow::Rigid;
  k.parts = "lateral lock + axle lock" + axis_parts(s);
  return k;
}

JointEffects WheelKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return {!d.spring.spring.is_free(), d.limit.enabled, d.motor.enabled};
}

// The linear impulse's size: the lateral rows and the suspension rows (limits, spring).
double WheelKind::tension(const JointSlot&, const float* impulse) {
  const float along = impulse[kAxisImpulses] - impulse[kAxisImpulses + 1] +
                      impulse[kAxisImpulses + 3];
  return double(Eigen::Vector3f(impulse[0], impulse[1], along).norm());
}

template <int W>
void WheelKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_axis_controls(g.axis, lane, d.limit, d.motor.speed, d.motor.max_torque, d.spring, j);
  g.sprung_mass[lane] = static_cast<float>(d.sprung_mass);
  g.steer_cos[lane] = static_cast<float>(std::cos(d.steering));
  g.steer_sin[lane] = static_cast<float>(std::sin(d.steering));
  for (int k = 0; k < 2; ++k) g.lateral_impulse[k][lane] = j.impulse[k];
  for (int k = 0; k < 2; ++k) g.lock_impulse[k][lane] = j.impulse[2 + k];
}

template <int W>
void WheelKind::write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  write_frame_lanes(g, lane,
                    world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b));
  write_axis_gaps(g.axis, lane, 0.0, d.limit, d.spring);  // the kernel measures all the travel
}

template <int W>
void WheelKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 2; ++k) out[k] = g.lateral_impulse[k][lane];
  for (int k = 0; k < 2; ++k) out[2 + k] = g.lock_impulse[k][lane];
  out[4] = 0.0f;
  read_axis_impulses(g.axis, lane, out);
}

template <int W>
void WheelKind::clear_impulses(Group<W>& g) {
  for (auto& row : g.lateral_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  for (auto& row : g.lock_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  simd::clear_axis_controls(g.axis);
}

JointSlot WheelKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  check_axis_spring(call, prefix + ".spring", def.spring);
  validation::finite(call, prefix + ".sprung_mass", def.sprung_mass);
  if (def.spring.spring.is_free() || def.spring.spring.is_absolute()) {
    // An absolute spring gives its k and c itself: the sprung mass is not used.
    validation::non_negative(call, prefix + ".sprung_mass", def.sprung_mass);
  } else if (!(def.sprung_mass >= validation::kMinMass)) {
    // Below a body's smallest mass the float spring's 1 / (h (h k + c)) overflows (the fuzzer's
    // kind of value: 1e-40 kg gave NaN bodies in the first step).
    validation::reject(call, prefix + ".sprung_mass", validation::format(def.sprung_mass),
                       "must be >= " + validation::format(validation::kMinMass) +
                           " kg with a soft spring: the spring's hertz refers to it (the chassis "
                           "mass over its wheels)");
  }
  if (def.sprung_mass > validation::kMaxMagnitude) {
    validation::reject(call, prefix + ".sprung_mass", validation::format(def.sprung_mass),
                       "must be <= " + validation::format(validation::kMaxMagnitude));
  }
  check_axis_limit(call, prefix + ".limit", def.limit);
  check_motor(call, prefix + ".motor", def.motor.speed, def.motor.max_torque, "max_torque");
  validation::finite(call, prefix + ".steering", def.steering);
  if (std::abs(def.steering) > validation::kMaxMagnitude) {
    validation::reject(call, prefix + ".steering", validation::format(def.steering),
                       "must lie within +-" + validation::format(validation::kMaxMagnitude));
  }
  j.type = type;
  j.def = stored;
  return j;
}

WheelJointDef WheelKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void WheelKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                        JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const WorldFrames f = world_frames(w, j, d.frame_a, d.frame_b);
  const Eigen::Vector3d up = f.a * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d axle =
      f.a * Eigen::Vector3d(std::cos(d.steering), std::sin(d.steering), 0.0);
  const Eigen::Vector3d forward = up.cross(axle);
  const Eigen::Vector3d gap = anchors.b - anchors.a;
  const double along = read_axis_controls(impulse, r) - r.motor_impulse;  // the motor turns
  r.impulse = double(impulse[0]) * axle + double(impulse[1]) * forward + along * up;
  // The axle lock's rows turn about -up and -forward where the axles agree (hinge_lock with
  // the perpendiculars up and forward), the motor about the axle.
  r.angular_impulse =
      -double(impulse[2]) * up - double(impulse[3]) * forward + r.motor_impulse * axle;
  r.position = gap.dot(up);
  r.error = (gap - r.position * up).norm();
  const Eigen::Vector3d wheel_axle = f.b * Eigen::Vector3d::UnitX();
  r.angular_error = std::acos(std::clamp(wheel_axle.dot(axle), -1.0, 1.0));
  r.effective_mass = slider_effective_mass(w, j, anchors, up);
}

void WheelKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  hash_axis_controls(h, d.limit, d.motor.enabled, d.motor.speed, d.motor.max_torque, d.spring);
  h.value(d.sprung_mass);
  h.value(d.steering);
}

SOFTSTEP_INSTANTIATE_KIND(WheelKind)
SOFTSTEP_INSTANTIATE_STEP_START(WheelKind)
SOFTSTEP_INSTANTIATE_JOINT_API(WheelJointDef)

}  // namespace softstep
