// What the joint kinds share on the core side (joint_common.hpp).
#include "joints/joint_common.hpp"

#include <limits>

#include "state_hasher.hpp"

namespace softstep {

JointSlot checked_joint_ends(const World::Impl& w, std::string_view call, std::string_view def,
                             BodyId a, BodyId b, const Eigen::Vector3d& local_anchor_a,
                             const Eigen::Vector3d& local_anchor_b, PointRows point_rows,
                             std::string_view anchor_a, std::string_view anchor_b) {
  const std::string prefix(def);
  JointSlot j;
  j.body_a = body_slot(w, call, prefix + ".body_a", a);
  j.body_b = body_slot(w, call, prefix + ".body_b", b);
  if (j.body_a == j.body_b) {
    validation::reject(call, prefix + ".body_b", "BodyId{" + std::to_string(b.index) + "}",
                       "a joint needs two different bodies (body_a is the same body)");
  }
  // Neither a static nor a kinematic body moves in response to a joint: between two of them
  // a joint has nothing to solve, and would hold a permanent error.
  const BodyType type_a = w.bodies[j.body_a].type, type_b = w.bodies[j.body_b].type;
  if (type_a != BodyType::Dynamic && type_b != BodyType::Dynamic) {
    const auto name = [](BodyType t) { return t == BodyType::Static ? "static" : "kinematic"; };
    validation::reject(
        call, prefix + ".body_b", "BodyId{" + std::to_string(b.index) + "} (" + name(type_b) + ")",
        std::string("a joint needs a dynamic body (body_a is ") + name(type_a) + ")");
  }
  validation::finite(call, prefix + "." + std::string(anchor_a), local_anchor_a);
  validation::finite(call, prefix + "." + std::string(anchor_b), local_anchor_b);
  const auto within_reach = [&](std::uint32_t body, const Eigen::Vector3d& anchor,
                                std::string_view name) {
    const BodySlot& s = w.bodies[body];
    if (point_rows == PointRows::No || s.type != BodyType::Dynamic) return;
    validation::point_lever(call, prefix + "." + std::string(name), validation::format(anchor),
                            anchor, s.mass, s.inertia);
  };
  within_reach(j.body_a, local_anchor_a, anchor_a);
  within_reach(j.body_b, local_anchor_b, anchor_b);
  j.local_anchor_a = local_anchor_a;
  j.local_anchor_b = local_anchor_b;
  return j;
}

void check_point_levers(const World::Impl& w, std::string_view call, std::string_view field,
                        std::uint32_t slot, double mass, const Eigen::Matrix3d& inertia) {
  for (const std::uint32_t joint : w.bodies[slot].joints) {
    const JointSlot& j = w.joints[joint];
    if (!j.alive || j.type == JointType::Distance) continue;
    const Eigen::Vector3d& anchor = j.body_a == slot ? j.local_anchor_a : j.local_anchor_b;
    validation::point_lever(call, field, validation::format(inertia), anchor, mass, inertia);
  }
}

WorldAnchors world_anchors(const World::Impl& w, const JointSlot& j) {
  const BodySlot& a = w.bodies[j.body_a];
  const BodySlot& b = w.bodies[j.body_b];
  return {a.position + a.orientation * j.local_anchor_a,
          b.position + b.orientation * j.local_anchor_b};
}

void hash_spring(StateHasher& h, const Spring& s) {
  h.value(s.hertz);
  h.value(s.damping_ratio);
  if (s.is_absolute()) {
    h.value(s.units);
    h.value(s.absolute_stiffness);
    h.value(s.absolute_damping);
  }
}

namespace {
// n.I^-1 n in world axes for a dynamic body (inverse_inertia is 0 otherwise).
double angular_compliance(const BodySlot& b, const Eigen::Vector3d& n) {
  const Eigen::Vector3d local = b.orientation.conjugate() * n;
  return local.dot(b.inverse_inertia * local);
}
double inverse_mass(const BodySlot& b) {
  return b.type == BodyType::Dynamic && b.mass > 0.0 ? 1.0 / b.mass : 0.0;
}
double inverse_or_infinity(double k) {
  return k > 0.0 ? 1.0 / k : std::numeric_limits<double>::infinity();
}
}  // namespace

double linear_effective_mass(const BodySlot& a, const BodySlot& b, const Eigen::Vector3d& arm_a,
                             const Eigen::Vector3d& arm_b, const Eigen::Vector3d& n) {
  return inverse_or_infinity(inverse_mass(a) + inverse_mass(b) +
                             angular_compliance(a, arm_a.cross(n)) +
                             angular_compliance(b, arm_b.cross(n)));
}

double angular_effective_mass(const BodySlot& a, const BodySlot& b, const Eigen::Vector3d& n) {
  return inverse_or_infinity(angular_compliance(a, n) + angular_compliance(b, n));
}

}  // namespace softstep
