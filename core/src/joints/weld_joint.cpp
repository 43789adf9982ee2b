// The weld joint: validation, lanes, reading (see weld_joint.hpp and
// simd/weld_joint_kernel.hpp).
#include "joints/weld_joint.hpp"

#include <algorithm>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "state_hasher.hpp"

namespace softstep {

namespace {
std::uint32_t half_bits(const Spring& s, std::uint32_t soft, std::uint32_t free) {
  return s.is_free() ? free : s.is_rigid() ? 0u : soft;
}
}  // namespace

std::uint32_t WeldKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return half_bits(d.linear, simd::kWeldLinearSoft, simd::kWeldLinearFree) |
         half_bits(d.angular, simd::kWeldAngularSoft, simd::kWeldAngularFree);
}

int WeldKind::rows(std::size_t, std::uint32_t s) {
  return ((s & simd::kWeldLinearFree) ? 0 : 3) + ((s & simd::kWeldAngularFree) ? 0 : 3);
}

bool WeldKind::needs_solve(std::size_t, std::uint32_t s) {
  return rows(0, s) > 0;
}

bool WeldKind::needs_relax(std::size_t, std::uint32_t s) {
  return simd::weld_half_runs(s, simd::kWeldLinearSoft, simd::kWeldLinearFree, false) ||
         simd::weld_half_runs(s, simd::kWeldAngularSoft, simd::kWeldAngularFree, false);
}

PlanKernel WeldKind::plan_kernel(std::size_t, std::uint32_t s) {
  const auto half = [&](std::uint32_t soft, std::uint32_t free, const char* name) {
    return std::string((s & free)   ? ""
                       : (s & soft) ? "soft "
                                    : "rigid ") +
           ((s & free) ? "" : name);
  };
  PlanKernel k{};
  k.type = type;
  k.row =
      (s & (simd::kWeldLinearSoft | simd::kWeldAngularSoft)) ? SpringRow::Soft : SpringRow::Rigid;
  const std::string angular = half(simd::kWeldAngularSoft, simd::kWeldAngularFree, "rotation lock");
  const std::string linear = half(simd::kWeldLinearSoft, simd::kWeldLinearFree, "point");
  k.parts = angular + (angular.empty() || linear.empty() ? "" : " + ") + linear;
  return k;
}

JointEffects WeldKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  const auto soft = [](const Spring& s) { return !s.is_rigid() && !s.is_free(); };
  return {soft(d.linear) || soft(d.angular), false, false};
}

double WeldKind::tension(const JointSlot&, const float* impulse) {
  return double(Eigen::Vector3f(impulse[0], impulse[1], impulse[2]).norm());
}

template <int W>
void WeldKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_spring_lanes(g.linear, lane, d.linear);
  fill_spring_lanes(g.angular, lane, d.angular);
  for (int k = 0; k < 3; ++k) g.point_impulse[k][lane] = j.impulse[k];
  for (int k = 0; k < 3; ++k) g.lock_impulse[k][lane] = j.impulse[3 + k];
}

template <int W>
void WeldKind::write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  write_frame_lanes(g, lane,
                    world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b));
}

template <int W>
void WeldKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 3; ++k) out[k] = g.point_impulse[k][lane];
  for (int k = 0; k < 3; ++k) out[3 + k] = g.lock_impulse[k][lane];
}

template <int W>
void WeldKind::clear_impulses(Group<W>& g) {
  for (auto& row : g.point_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  for (auto& row : g.lock_impulse) std::fill(std::begin(row), std::end(row), 0.0f);
}

JointSlot WeldKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  validation::relative_spring(call, prefix + ".linear", def.linear);
  validation::relative_spring(call, prefix + ".angular", def.angular);
  j.type = type;
  j.def = stored;
  return j;
}

WeldJointDef WeldKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void WeldKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                       JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const WorldFrames f = world_frames(w, j, d.frame_a, d.frame_b);
  r.impulse = Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
  r.angular_impulse = Eigen::Vector3d(impulse[3], impulse[4], impulse[5]);
  r.error = (anchors.b - anchors.a).norm();
  r.angular_error = Eigen::AngleAxisd(f.b * f.a.conjugate()).angle();
}

void WeldKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  h.value(d.linear.hertz);
  h.value(d.linear.damping_ratio);
  h.value(d.angular.hertz);
  h.value(d.angular.damping_ratio);
}

SOFTSTEP_INSTANTIATE_KIND(WeldKind)
SOFTSTEP_INSTANTIATE_STEP_START(WeldKind)
SOFTSTEP_INSTANTIATE_JOINT_API(WeldJointDef)

}  // namespace softstep
