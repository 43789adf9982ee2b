// The distance joint: validation, lanes, reading (see distance_joint.hpp and
// simd/distance_joint_kernel.hpp).
#include "joints/distance_joint.hpp"

#include <algorithm>
#include <cmath>

#include "joints/joint_api.hpp"
#include "joints/joint_common.hpp"
#include "state_hasher.hpp"

namespace softstep {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

simd::JointFeatures features_of(const DistanceJointDef& d) {
  const simd::RowKind row = d.spring.is_rigid()  ? simd::RowKind::Rigid
                            : d.spring.is_free() ? simd::RowKind::Free
                                                 : simd::RowKind::Soft;
  simd::JointFeatures f{row, false, false};
  if (row != simd::RowKind::Rigid) {
    f.lower = d.min_length > 0.0;
    f.upper = d.max_length < kInf;
  }
  return f;
}
}  // namespace

std::uint8_t DistanceKind::variant(const JointSlot& j, bool specialize) {
  if (!specialize) return 0;
  const simd::JointFeatures f = features_of(std::get<Def>(j.def));
  for (std::size_t i = 1; i < variants.size(); ++i) {
    if (variants[i] == f) return static_cast<std::uint8_t>(i);
  }
  return 0;  // every signature has a variant; the general kernel would do too
}

// The spring row (unless free) and the limit rows; the general kernel evaluates all three.
int DistanceKind::rows(std::size_t v, std::uint32_t) {
  const simd::JointFeatures f = variants[v];
  if (f.row == simd::RowKind::Any) return 3;
  return (f.row == simd::RowKind::Free ? 0 : 1) + (f.lower ? 1 : 0) + (f.upper ? 1 : 0);
}

PlanKernel DistanceKind::plan_kernel(std::size_t v, std::uint32_t) {
  const simd::JointFeatures f = variants[v];
  PlanKernel k{};
  k.type = type;
  k.row = static_cast<SpringRow>(f.row);
  k.lower_limit = f.lower;
  k.upper_limit = f.upper;
  k.parts = f.row == simd::RowKind::Free ? "" : "axis";
  if (f.lower) k.parts += k.parts.empty() ? "lower" : " + lower";
  if (f.upper) k.parts += k.parts.empty() ? "upper" : " + upper";
  k.compiled_variant = v != 0;
  return k;
}

JointEffects DistanceKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  const bool rigid = d.spring.is_rigid();
  return {!rigid && !d.spring.is_free(), !rigid && (d.min_length > 0.0 || d.max_length < kInf),
          false};
}

double DistanceKind::tension(const JointSlot&, const float* impulse) {
  return std::abs(double(impulse[0] + impulse[1] - impulse[2]));
}

template <int W>
void DistanceKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  fill_spring_lanes(g, lane, d.spring);  // hertz 0 when absolute: k and c below instead
  g.spring_stiffness[lane] = static_cast<float>(d.spring.absolute_stiffness);
  g.spring_damping[lane] = static_cast<float>(d.spring.absolute_damping);
  const bool rigid = d.spring.is_rigid();
  g.rest_length[lane] = static_cast<float>(d.rest_length);
  g.min_length[lane] = static_cast<float>(d.min_length);
  g.max_length[lane] = static_cast<float>(d.max_length);
  g.lower_enabled[lane] = (!rigid && d.min_length > 0.0) ? 1.0f : 0.0f;
  g.upper_enabled[lane] = (!rigid && d.max_length < kInf) ? 1.0f : 0.0f;
  g.impulse[lane] = j.impulse[0];
  g.lower_impulse[lane] = j.impulse[1];
  g.upper_impulse[lane] = j.impulse[2];
}

template <int W>
void DistanceKind::read_impulses(const Group<W>& g, int lane, float* out) {
  out[0] = g.impulse[lane];
  out[1] = g.lower_impulse[lane];
  out[2] = g.upper_impulse[lane];
}

template <int W>
void DistanceKind::clear_impulses(Group<W>& g) {
  std::fill(std::begin(g.impulse), std::end(g.impulse), 0.0f);
  std::fill(std::begin(g.lower_impulse), std::end(g.lower_impulse), 0.0f);
  std::fill(std::begin(g.upper_impulse), std::end(g.upper_impulse), 0.0f);
}

JointSlot DistanceKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  JointSlot j = checked_joint_ends(w, call, "DistanceJointDef", def.body_a, def.body_b,
                                   def.local_anchor_a, def.local_anchor_b, PointRows::No);
  validation::spring(call, "DistanceJointDef.spring", def.spring);
  validation::non_negative(call, "DistanceJointDef.rest_length", def.rest_length);
  validation::non_negative(call, "DistanceJointDef.min_length", def.min_length);
  if (std::isnan(def.max_length) || def.max_length < def.min_length ||
      (def.max_length > validation::kMaxMagnitude && def.max_length != kInf)) {
    validation::reject(call, "DistanceJointDef.max_length", validation::format(def.max_length),
                       "must be >= min_length (" + validation::format(def.min_length) +
                           ") and <= " + validation::format(validation::kMaxMagnitude) +
                           "; +infinity for no upper limit");
  }
  j.type = type;
  Def stored = def;
  stored.rest_length = std::clamp(def.rest_length, def.min_length, def.max_length);
  j.def = stored;
  return j;
}

DistanceJointDef DistanceKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void DistanceKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                           JointReading& r) {
  const Def& def = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const Eigen::Vector3d d = anchors.b - anchors.a;
  const double length = d.norm();
  const Eigen::Vector3d n = length > 1e-9 ? Eigen::Vector3d(d / length) : Eigen::Vector3d::Zero();
  r.impulse = double(impulse[0] + impulse[1] - impulse[2]) * n;
  if (def.spring.is_free()) {
    r.error = std::max({0.0, def.min_length - length, length - def.max_length});
  } else {
    r.error = std::abs(length - def.rest_length);
  }
  r.position = length;
  r.limit_impulse = double(impulse[1]) - double(impulse[2]);
  r.spring_impulse = impulse[0];
  // The axis row's arms (distance_joint_kernel.hpp): each anchor from its body's centre.
  const BodySlot& a = w.bodies[j.body_a];
  const BodySlot& b = w.bodies[j.body_b];
  r.effective_mass = length > 1e-9 ? linear_effective_mass(a, b, anchors.a - a.position,
                                                           anchors.b - b.position, n)
                                   : std::numeric_limits<double>::quiet_NaN();
}

// The bytes the state hash took before the registry, so the golden hashes still hold.
void DistanceKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_spring(h, d.spring);
  h.value(d.rest_length);
  h.value(d.min_length);
  h.value(d.max_length);
}

SOFTSTEP_INSTANTIATE_KIND(DistanceKind)
SOFTSTEP_INSTANTIATE_JOINT_API(DistanceJointDef)

JointId World::create_distance_joint(const DistanceJointDef& def) {
  return create_joint_of(*this, *impl_, "create_distance_joint", def);
}

DistanceJointDef World::distance_joint(JointId id) const {
  return joint_def<DistanceJointDef>(id);
}

}  // namespace softstep
