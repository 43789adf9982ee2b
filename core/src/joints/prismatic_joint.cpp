// The prismatic joint: validation, lanes, reading (see prismatic_joint.hpp and
// simd/prismatic_joint_kernel.hpp).
#include "joints/prismatic_joint.hpp"

#include <algorithm>
#include <cmath>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "state_hasher.hpp"

namespace softstep {

std::uint32_t PrismaticKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return axis_signature(d.limit, d.motor.enabled, d.spring);
}

int PrismaticKind::rows(std::size_t, std::uint32_t s) {
  return 5 + axis_control_rows(s);  // the 5 lock rows, then the axis controls
}

PlanKernel PrismaticKind::plan_kernel(std::size_t, std::uint32_t s) {
  PlanKernel k{};
  k.type = type;
  k.row = SpringRow::Rigid;
  k.parts = "lateral lock + rotation lock" + axis_parts(s);
  return k;
}

JointEffects PrismaticKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return {!d.spring.spring.is_free(), d.limit.enabled, d.motor.enabled};
}

// The linear impulse's size: the lateral rows and the axis rows (limit, motor, spring).
double PrismaticKind::tension(const JointSlot&, const float* impulse) {
  const float along = impulse[5] - impulse[6] + impulse[7] + impulse[8];
  return double(Eigen::Vector3f(impulse[0], impulse[1], along).norm());
}

template <int W>
void PrismaticKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_axis_controls(g.axis, lane, d.limit, d.motor.speed, d.motor.max_force, d.spring, j);
  for (int k = 0; k < 2; ++k) g.lateral_impulse[k][lane] = j.impulse[k];
  for (int k = 0; k < 3; ++k) g.lock_impulse[k][lane] = j.impulse[2 + k];
}

template <int W>
void PrismaticKind::write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  write_frame_lanes(g, lane,
                    world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b));
  write_axis_gaps(g.axis, lane, 0.0, d.limit, d.spring);  // the kernel measures all of it
}

template <int W>
void PrismaticKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 2; ++k) out[k] = g.lateral_impulse[k][lane];
  for (int k = 0; k < 3; ++k) out[2 + k] = g.lock_impulse[k][lane];
  read_axis_impulses(g.axis, lane, out);
}

template <int W>
void PrismaticKind::clear_impulses(Group<W>& g) {
  for (auto& row : g.lateral_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  for (auto& row : g.lock_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  simd::clear_axis_controls(g.axis);
}

JointSlot PrismaticKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  check_axis_limit(call, prefix + ".limit", def.limit);
  check_motor(call, prefix + ".motor", def.motor.speed, def.motor.max_force, "max_force");
  check_axis_spring(call, prefix + ".spring", def.spring);
  j.type = type;
  j.def = stored;
  return j;
}

PrismaticJointDef PrismaticKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void PrismaticKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                            JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const WorldFrames f = world_frames(w, j, d.frame_a, d.frame_b);
  const Eigen::Vector3d x_a = f.a * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y_a = f.a * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z_a = f.a * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d gap = anchors.b - anchors.a;
  const double along = read_axis_controls(impulse, r);
  r.impulse = double(impulse[0]) * x_a + double(impulse[1]) * y_a + along * z_a;
  r.angular_impulse = Eigen::Vector3d(impulse[2], impulse[3], impulse[4]);
  r.position = gap.dot(z_a);
  r.error = (gap - r.position * z_a).norm();
  r.angular_error = Eigen::AngleAxisd(f.b * f.a.conjugate()).angle();
  r.effective_mass = slider_effective_mass(w, j, anchors, z_a);
}

void PrismaticKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  hash_axis_controls(h, d.limit, d.motor.enabled, d.motor.speed, d.motor.max_force, d.spring);
}

SOFTSTEP_INSTANTIATE_KIND(PrismaticKind)
SOFTSTEP_INSTANTIATE_STEP_START(PrismaticKind)
SOFTSTEP_INSTANTIATE_JOINT_API(PrismaticJointDef)

}  // namespace softstep
