// The revolute joint: validation, lanes, the unwrapped angle, reading (see revolute_joint.hpp
// and simd/revolute_joint_kernel.hpp).
#include "joints/revolute_joint.hpp"

#include <algorithm>
#include <cmath>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "state_hasher.hpp"

namespace softstep {

std::uint32_t RevoluteKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return axis_signature(d.limit, d.motor.enabled, d.spring);
}

int RevoluteKind::rows(std::size_t, std::uint32_t s) {
  return 5 + axis_control_rows(s);  // the 5 lock rows, then the axis controls
}

PlanKernel RevoluteKind::plan_kernel(std::size_t, std::uint32_t s) {
  PlanKernel k{};
  k.type = type;
  k.row = SpringRow::Rigid;
  k.parts = "point + hinge lock" + axis_parts(s);
  return k;
}

JointEffects RevoluteKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return {!d.spring.spring.is_free(), d.limit.enabled, d.motor.enabled};
}

double RevoluteKind::tension(const JointSlot&, const float* impulse) {
  return double(Eigen::Vector3f(impulse[0], impulse[1], impulse[2]).norm());
}

template <int W>
void RevoluteKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_axis_controls(g.axis, lane, d.limit, d.motor.speed, d.motor.max_torque, d.spring, j);
  for (int k = 0; k < 3; ++k) g.point_impulse[k][lane] = j.impulse[k];
  for (int k = 0; k < 2; ++k) g.lock_impulse[k][lane] = j.impulse[3 + k];
}

// The angle is kept unwrapped in double: each step it moves to the representative of the
// wrapped angle nearest to where it was (at most half a turn away: revolute.hpp).
template <int W>
void RevoluteKind::write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  const WorldFrames f = world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b);
  write_frame_lanes(g, lane, f);
  const double wrapped = wrapped_hinge_angle(f);
  j.angle = unwrap_angle(j.angle, wrapped);
  g.angle_start[lane] = static_cast<float>(wrapped);
  write_axis_gaps(g.axis, lane, j.angle, d.limit, d.spring);
}

template <int W>
void RevoluteKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 3; ++k) out[k] = g.point_impulse[k][lane];
  for (int k = 0; k < 2; ++k) out[3 + k] = g.lock_impulse[k][lane];
  read_axis_impulses(g.axis, lane, out);
}

template <int W>
void RevoluteKind::clear_impulses(Group<W>& g) {
  for (auto& row : g.point_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  for (auto& row : g.lock_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  simd::clear_axis_controls(g.axis);
}

JointSlot RevoluteKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  check_axis_limit(call, prefix + ".limit", def.limit);
  check_motor(call, prefix + ".motor", def.motor.speed, def.motor.max_torque, "max_torque");
  check_axis_spring(call, prefix + ".spring", def.spring);
  j.type = type;
  j.def = stored;
  j.angle = wrapped_hinge_angle(world_frames(w, j, stored.frame_a, stored.frame_b));
  return j;
}

RevoluteJointDef RevoluteKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void RevoluteKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                           JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const WorldFrames f = world_frames(w, j, d.frame_a, d.frame_b);
  const Eigen::Vector3d x_a = f.a * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y_a = f.a * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z_a = f.a * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_b = f.b * Eigen::Vector3d::UnitZ();
  r.impulse = Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
  const double about_axis = read_axis_controls(impulse, r);
  r.angular_impulse =
      double(impulse[3]) * y_a.cross(z_b) + double(impulse[4]) * z_b.cross(x_a) + about_axis * z_a;
  r.error = (anchors.b - anchors.a).norm();
  r.angular_error = std::acos(std::clamp(z_a.dot(z_b), -1.0, 1.0));
  r.position = unwrap_angle(j.angle, wrapped_hinge_angle(f));
  r.effective_mass = angular_effective_mass(w.bodies[j.body_a], w.bodies[j.body_b], z_a);
}

void RevoluteKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  hash_axis_controls(h, d.limit, d.motor.enabled, d.motor.speed, d.motor.max_torque, d.spring);
  h.value(j.angle);
}

SOFTSTEP_INSTANTIATE_KIND(RevoluteKind)
SOFTSTEP_INSTANTIATE_STEP_START(RevoluteKind)
SOFTSTEP_INSTANTIATE_JOINT_API(RevoluteJointDef)

}  // namespace softstep
