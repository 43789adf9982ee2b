// The ball joint: validation, lanes, reading (see ball_joint.hpp and simd/ball_joint_kernel.hpp).
#include "joints/ball_joint.hpp"

#include "joints/joint_api.hpp"
#include "joints/joint_common.hpp"
#include "state_hasher.hpp"

namespace softstep {

std::uint8_t BallKind::variant(const JointSlot& j, bool specialize) {
  if (!specialize) return 0;
  const Spring& s = std::get<Def>(j.def).spring;
  return s.is_rigid() ? 1 : s.is_free() ? 3 : 2;
}

int BallKind::rows(std::size_t v, std::uint32_t) {
  return variants[v].row == simd::RowKind::Free ? 0 : 3;
}

PlanKernel BallKind::plan_kernel(std::size_t v, std::uint32_t) {
  PlanKernel k{};
  k.type = type;
  k.row = static_cast<SpringRow>(variants[v].row);
  k.parts = "point";
  k.compiled_variant = v != 0;
  return k;
}

JointEffects BallKind::effects(const JointSlot& j) {
  const Spring& s = std::get<Def>(j.def).spring;
  return {!s.is_rigid() && !s.is_free(), false, false};
}

// The norm in float, as the geometric inertia took it before the registry (golden hashes).
double BallKind::tension(const JointSlot&, const float* impulse) {
  return double(Eigen::Vector3f(impulse[0], impulse[1], impulse[2]).norm());
}

template <int W>
void BallKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  fill_spring_lanes(g, lane, std::get<Def>(j.def).spring);
  for (int k = 0; k < 3; ++k) g.impulse[k][lane] = j.impulse[k];
}

template <int W>
void BallKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 3; ++k) out[k] = g.impulse[k][lane];
}

template <int W>
void BallKind::clear_impulses(Group<W>& g) {
  for (auto& row : g.impulse) std::fill(std::begin(row), std::end(row), 0.0f);
}

JointSlot BallKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  JointSlot j = checked_joint_ends(w, call, "BallJointDef", def.body_a, def.body_b,
                                   def.local_anchor_a, def.local_anchor_b, PointRows::Yes);
  validation::relative_spring(call, "BallJointDef.spring", def.spring);
  j.type = type;
  j.def = def;
  return j;
}

BallJointDef BallKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void BallKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                       JointReading& r) {
  const WorldAnchors anchors = world_anchors(w, j);
  r.impulse = Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
  r.error = (anchors.b - anchors.a).norm();
}

// The bytes the state hash took before the registry (spring, then three zero lengths), so the
// golden hashes still hold.
void BallKind::hash(StateHasher& h, const JointSlot& j) {
  const Spring& s = std::get<Def>(j.def).spring;
  h.value(s.hertz);
  h.value(s.damping_ratio);
  for (int k = 0; k < 3; ++k) h.value(0.0);
}

SOFTSTEP_INSTANTIATE_KIND(BallKind)
SOFTSTEP_INSTANTIATE_JOINT_API(BallJointDef)

JointId World::create_ball_joint(const BallJointDef& def) {
  return create_joint_of(*this, *impl_, "create_ball_joint", def);
}

BallJointDef World::ball_joint(JointId id) const {
  return joint_def<BallJointDef>(id);
}

}  // namespace softstep
