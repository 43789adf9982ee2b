#include "joint_formats.hpp"

#include <stdexcept>

namespace softstep::scene {

BodyIndex::BodyIndex(const std::vector<BodyId>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].index >= of_slot_.size()) of_slot_.resize(bodies[i].index + 1, 0);
    of_slot_[bodies[i].index] = i;
  }
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json spring_json(const Spring& spring) {
  if (spring.is_rigid()) return "rigid";
  return {{"hertz", spring.hertz}, {"damping_ratio", spring.damping_ratio}};
}

namespace {

// The two ends every joint has: bodies by file index, anchors in each body's frame, a spring.
template <class Def>
void read_ends(ObjectReader& fields, const std::vector<BodyId>& bodies, Def& def) {
  def.body_a = fields.body("body_a", bodies);
  def.body_b = fields.body("body_b", bodies);
  def.local_anchor_a = fields.vec3("local_anchor_a", def.local_anchor_a);
  def.local_anchor_b = fields.vec3("local_anchor_b", def.local_anchor_b);
  def.spring = fields.spring("spring", def.spring);
}

template <class Def>
void write_ends(const Def& def, const BodyIndex& index, nlohmann::json& out) {
  out["body_a"] = index(def.body_a);
  out["body_b"] = index(def.body_b);
  out["local_anchor_a"] = vector_json(def.local_anchor_a);
  out["local_anchor_b"] = vector_json(def.local_anchor_b);
  out["spring"] = spring_json(def.spring);
}

JointId read_ball(World& world, ObjectReader& fields, const std::vector<BodyId>& bodies) {
  BallJointDef def;
  read_ends(fields, bodies, def);
  fields.no_other_keys();
  return fields.call([&] { return world.create_ball_joint(def); });
}

void write_ball(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  write_ends(world.ball_joint(id), index, out);
}

JointId read_distance(World& world, ObjectReader& fields, const std::vector<BodyId>& bodies) {
  DistanceJointDef def;
  read_ends(fields, bodies, def);
  def.rest_length = fields.number("rest_length", def.rest_length);
  def.min_length = fields.number("min_length", def.min_length);
  def.max_length = fields.number("max_length", def.max_length);  // missing: no upper limit
  fields.no_other_keys();
  return fields.call([&] { return world.create_distance_joint(def); });
}

void write_distance(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const DistanceJointDef def = world.distance_joint(id);
  write_ends(def, index, out);
  out["rest_length"] = def.rest_length;
  out["min_length"] = def.min_length;
  if (std::isfinite(def.max_length)) out["max_length"] = def.max_length;
}

constexpr JointFormat kJointFormats[] = {
    {"ball", JointType::Ball, read_ball, write_ball},
    {"distance", JointType::Distance, read_distance, write_distance},
};

}  // namespace

std::span<const JointFormat> joint_formats() {
  return kJointFormats;
}

const JointFormat* joint_format(const std::string& name) {
  for (const JointFormat& f : kJointFormats) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

const JointFormat& joint_format(JointType type) {
  for (const JointFormat& f : kJointFormats) {
    if (f.type == type) return f;
  }
  throw std::logic_error("scene files: no format for this joint type");
}

}  // namespace softstep::scene
