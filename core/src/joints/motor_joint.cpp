// The motor joint: validation, lanes, reading (see motor_joint.hpp and
// simd/motor_joint_kernel.hpp).
#include "joints/motor_joint.hpp"

#include <algorithm>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "joints/weld_joint.hpp"
#include "state_hasher.hpp"

namespace softstep {

std::uint32_t MotorKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return (d.linear.is_rigid() ? 0u : simd::kMotorLinearSoft) |
         (d.angular.is_rigid() ? 0u : simd::kMotorAngularSoft);
}

int MotorKind::rows(std::size_t, std::uint32_t) {
  return 6;
}

// A drive, not a lock: never relaxed (motor_joint_kernel.hpp).
bool MotorKind::needs_relax(std::size_t, std::uint32_t) {
  return false;
}

PlanKernel MotorKind::plan_kernel(std::size_t, std::uint32_t s) {
  PlanKernel k{};
  k.type = type;
  k.row = (s & (simd::kMotorLinearSoft | simd::kMotorAngularSoft)) ? SpringRow::Soft
                                                                     : SpringRow::Rigid;
  k.parts = std::string((s & simd::kMotorAngularSoft) ? "soft" : "rigid") +
            " capped rotation + " + ((s & simd::kMotorLinearSoft) ? "soft" : "rigid") +
            " capped point";
  return k;
}

JointEffects MotorKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return {!d.linear.is_rigid() || !d.angular.is_rigid(), false, true};
}

double MotorKind::tension(const JointSlot&, const float* impulse) {
  return double(Eigen::Vector3f(impulse[0], impulse[1], impulse[2]).norm());
}

template <int W>
void MotorKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_spring_lanes(g.linear, lane, d.linear);
  fill_spring_lanes(g.angular, lane, d.angular);
  g.max_force[lane] = static_cast<float>(d.max_force);
  g.max_torque[lane] = static_cast<float>(d.max_torque);
  for (int k = 0; k < 3; ++k) g.point_impulse[k][lane] = j.impulse[k];
  for (int k = 0; k < 3; ++k) g.lock_impulse[k][lane] = j.impulse[3 + k];
}

template <int W>
void MotorKind::write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  write_frame_lanes(g, lane,
                    world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b));
}

// The impulses sit in the lanes the motor joint shares with the weld joint.
template <int W>
void MotorKind::read_impulses(const Group<W>& g, int lane, float* out) {
  WeldKind::read_impulses<W>(g, lane, out);
}

template <int W>
void MotorKind::clear_impulses(Group<W>& g) {
  WeldKind::clear_impulses<W>(g);
}

JointSlot MotorKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  for (const auto& [name, value] :
       {std::pair{".max_force", def.max_force}, {".max_torque", def.max_torque}}) {
    validation::non_negative(call, prefix + name, value);
    if (value > validation::kMaxMagnitude) {
      validation::reject(call, prefix + name, validation::format(value),
                         "must be <= " + validation::format(validation::kMaxMagnitude));
    }
  }
  for (const auto& [name, spring] :
       {std::pair{".linear", def.linear}, std::pair{".angular", def.angular}}) {
    validation::relative_spring(call, prefix + name, spring);
    if (spring.is_free()) {
      validation::reject(call, prefix + name + ".hertz", "0",
                         "a motor joint's half is rigid or soft (a zero cap leaves it idle)");
    }
  }
  j.type = type;
  j.def = stored;
  return j;
}

MotorJointDef MotorKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void MotorKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                        JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const WorldFrames f = world_frames(w, j, d.frame_a, d.frame_b);
  r.impulse = Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
  r.angular_impulse = Eigen::Vector3d(impulse[3], impulse[4], impulse[5]);
  r.error = (anchors.b - anchors.a).norm();
  r.angular_error = Eigen::AngleAxisd(f.b * f.a.conjugate()).angle();
}

void MotorKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  h.value(d.max_force);
  h.value(d.max_torque);
  h.value(d.linear.hertz);
  h.value(d.linear.damping_ratio);
  h.value(d.angular.hertz);
  h.value(d.angular.damping_ratio);
}

SOFTSTEP_INSTANTIATE_KIND(MotorKind)
SOFTSTEP_INSTANTIATE_STEP_START(MotorKind)
SOFTSTEP_INSTANTIATE_JOINT_API(MotorJointDef)

}  // namespace softstep
