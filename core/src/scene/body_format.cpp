#include "body_format.hpp"

#include "joint_formats.hpp"

namespace softstep::scene {

namespace {

const char* body_type_name(BodyType type) {
  return type == BodyType::Static      ? "static"
         : type == BodyType::Kinematic ? "kinematic"
                                       : "dynamic";
}

BodyType body_type(ObjectReader& fields) {
  const std::string type = fields.text("type");
  if (type == "static") return BodyType::Static;
  if (type == "kinematic") return BodyType::Kinematic;
  if (type == "dynamic") return BodyType::Dynamic;
  fail(fields.source(), fields.path_of("type"),
       "expected \"static\", \"kinematic\" or \"dynamic\"");
}

}  // namespace

BodyDef read_body(ObjectReader& fields) {
  BodyDef def;
  def.type = body_type(fields);
  def.position = fields.vec3("position");
  def.orientation = fields.quaternion("orientation", def.orientation);
  def.linear_velocity = fields.vec3("linear_velocity", def.linear_velocity);
  def.angular_velocity = fields.vec3("angular_velocity", def.angular_velocity);
  def.mass = fields.number("mass", def.mass);
  def.inertia = fields.mat3("inertia", def.inertia);
  def.gravity_scale = fields.number("gravity_scale", def.gravity_scale);
  def.linear_damping = fields.number("linear_damping", def.linear_damping);
  def.angular_damping = fields.number("angular_damping", def.angular_damping);
  def.never_sleep = fields.boolean("never_sleep", def.never_sleep);
  fields.no_other_keys();
  return def;
}

PendingLoads read_pending_loads(ObjectReader& fields) {
  PendingLoads loads;
  loads.force = fields.vec3("force", loads.force);
  loads.torque = fields.vec3("torque", loads.torque);
  return loads;
}

void write_pending_loads(const BodyState& state, nlohmann::json& body) {
  if (!state.force.isZero(0.0)) body["force"] = vector_json(state.force);
  if (!state.torque.isZero(0.0)) body["torque"] = vector_json(state.torque);
}

nlohmann::json body_json(const BodyDef& b) {
  const Quaternion& q = b.orientation;
  nlohmann::json j = {{"type", body_type_name(b.type)},
                      {"position", vector_json(b.position)},
                      {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                      {"linear_velocity", vector_json(b.linear_velocity)},
                      {"angular_velocity", vector_json(b.angular_velocity)}};
  // Static and kinematic bodies have no mass (the API ignores one given).
  if (b.type == BodyType::Dynamic) {
    j["mass"] = b.mass;
    j["inertia"] = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) j["inertia"].push_back(vector_json(b.inertia.row(r)));
  }
  j["gravity_scale"] = b.gravity_scale;
  j["linear_damping"] = b.linear_damping;
  j["angular_damping"] = b.angular_damping;
  j["never_sleep"] = b.never_sleep;
  return j;
}

BodyDef body_def(const BodyState& s) {
  BodyDef def;
  def.type = s.type;
  def.position = s.position;
  def.orientation = s.orientation;
  def.linear_velocity = s.linear_velocity;
  def.angular_velocity = s.angular_velocity;
  if (s.type == BodyType::Dynamic) {
    def.mass = s.mass;
    def.inertia = s.inertia;
  }
  def.gravity_scale = s.gravity_scale;
  def.linear_damping = s.linear_damping;
  def.angular_damping = s.angular_damping;
  def.never_sleep = s.never_sleep;
  return def;
}

}  // namespace softstep::scene
