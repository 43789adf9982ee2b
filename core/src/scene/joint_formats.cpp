#include "joint_formats.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "softstep/softstep.hpp"

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
  if (spring.is_absolute()) {
    return {{"absolute_stiffness", spring.absolute_stiffness},
            {"absolute_damping", spring.absolute_damping}};
  }
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

BallJointDef read_ball(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  BallJointDef def;
  read_ends(fields, bodies, def);
  fields.no_other_keys();
  return def;
}

void write_ball(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  write_ends(world.ball_joint(id), index, out);
}

DistanceJointDef read_distance(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  DistanceJointDef def;
  read_ends(fields, bodies, def);
  def.rest_length = fields.number("rest_length", def.rest_length);
  def.min_length = fields.number("min_length", def.min_length);
  def.max_length = fields.number("max_length", def.max_length);  // missing: no upper limit
  fields.no_other_keys();
  return def;
}

void write_distance(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const DistanceJointDef def = world.distance_joint(id);
  write_ends(def, index, out);
  out["rest_length"] = def.rest_length;
  out["min_length"] = def.min_length;
  if (std::isfinite(def.max_length)) out["max_length"] = def.max_length;
}

// The angular joints (revolute, prismatic, weld): bodies and a frame on each, as the Defs in
// softstep/joints/*.hpp hold them. Nested objects carry the Defs' own field names, so an
// InvalidArgument naming "RevoluteJointDef.frame_a.local_axis" lands at .../frame_a/local_axis.

JointFrame read_frame(ObjectReader& parent, const char* key) {
  ObjectReader f(parent.source(), parent.object(key), parent.path_of(key));
  JointFrame frame;
  frame.local_anchor = f.vec3("local_anchor", frame.local_anchor);
  frame.local_axis = f.vec3("local_axis", frame.local_axis);
  frame.local_reference = f.vec3("local_reference", frame.local_reference);
  f.no_other_keys();
  return frame;
}

nlohmann::json frame_json(const JointFrame& frame) {
  return {{"local_anchor", vector_json(frame.local_anchor)},
          {"local_axis", vector_json(frame.local_axis)},
          {"local_reference", vector_json(frame.local_reference)}};
}

template <class Def>
void read_frames(ObjectReader& fields, const std::vector<BodyId>& bodies, Def& def) {
  def.body_a = fields.body("body_a", bodies);
  def.body_b = fields.body("body_b", bodies);
  def.frame_a = read_frame(fields, "frame_a");
  def.frame_b = read_frame(fields, "frame_b");
}

template <class Def>
void write_frames(const Def& def, const BodyIndex& index, nlohmann::json& out) {
  out["body_a"] = index(def.body_a);
  out["body_b"] = index(def.body_b);
  out["frame_a"] = frame_json(def.frame_a);
  out["frame_b"] = frame_json(def.frame_b);
}

// A missing bound is no bound (JSON has no infinity).
AxisLimit read_limit(ObjectReader& parent, const char* key = "limit") {
  ObjectReader f(parent.source(), parent.object(key), parent.path_of(key));
  AxisLimit limit;
  limit.enabled = f.boolean("enabled", limit.enabled);
  limit.lower = f.number("lower", -std::numeric_limits<double>::infinity());
  limit.upper = f.number("upper", std::numeric_limits<double>::infinity());
  f.no_other_keys();
  return limit;
}

nlohmann::json limit_json(const AxisLimit& limit) {
  nlohmann::json j = {{"enabled", limit.enabled}};
  if (std::isfinite(limit.lower)) j["lower"] = limit.lower;
  if (std::isfinite(limit.upper)) j["upper"] = limit.upper;
  return j;
}

// The motor's torque or force field: "max_torque" (revolute) or "max_force" (prismatic).
template <class Motor>
Motor read_motor(ObjectReader& parent, const char* max_key, double Motor::*max) {
  ObjectReader f(parent.source(), parent.object("motor"), parent.path_of("motor"));
  Motor motor;
  motor.enabled = f.boolean("enabled", motor.enabled);
  motor.speed = f.number("speed", motor.speed);
  motor.*max = f.number(max_key, motor.*max);
  f.no_other_keys();
  return motor;
}

template <class Motor>
nlohmann::json motor_json(const Motor& motor, const char* max_key, double Motor::*max) {
  return {{"enabled", motor.enabled}, {"speed", motor.speed}, {max_key, motor.*max}};
}

AxisSpring read_axis_spring(ObjectReader& parent) {
  ObjectReader f(parent.source(), parent.object("spring"), parent.path_of("spring"));
  AxisSpring spring;
  spring.spring = f.spring("spring", spring.spring);
  spring.target = f.number("target", spring.target);
  f.no_other_keys();
  return spring;
}

nlohmann::json axis_spring_json(const AxisSpring& spring) {
  return {{"spring", spring_json(spring.spring)}, {"target", spring.target}};
}

RevoluteJointDef read_revolute(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  RevoluteJointDef def;
  read_frames(fields, bodies, def);
  def.limit = read_limit(fields);
  def.motor = read_motor(fields, "max_torque", &AngularMotor::max_torque);
  def.spring = read_axis_spring(fields);
  fields.no_other_keys();
  return def;
}

void write_revolute(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const auto def = world.joint_def<RevoluteJointDef>(id);
  write_frames(def, index, out);
  out["limit"] = limit_json(def.limit);
  out["motor"] = motor_json(def.motor, "max_torque", &AngularMotor::max_torque);
  out["spring"] = axis_spring_json(def.spring);
}

PrismaticJointDef read_prismatic(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  PrismaticJointDef def;
  read_frames(fields, bodies, def);
  def.limit = read_limit(fields);
  def.motor = read_motor(fields, "max_force", &LinearMotor::max_force);
  def.spring = read_axis_spring(fields);
  fields.no_other_keys();
  return def;
}

void write_prismatic(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const auto def = world.joint_def<PrismaticJointDef>(id);
  write_frames(def, index, out);
  out["limit"] = limit_json(def.limit);
  out["motor"] = motor_json(def.motor, "max_force", &LinearMotor::max_force);
  out["spring"] = axis_spring_json(def.spring);
}

WeldJointDef read_weld(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  WeldJointDef def;
  read_frames(fields, bodies, def);
  def.linear = fields.spring("linear", def.linear);
  def.angular = fields.spring("angular", def.angular);
  fields.no_other_keys();
  return def;
}

void write_weld(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const auto def = world.joint_def<WeldJointDef>(id);
  write_frames(def, index, out);
  out["linear"] = spring_json(def.linear);
  out["angular"] = spring_json(def.angular);
}

// The swing-twist joint: the cone, the twist limit (as an axis limit), the orientation spring
// (its target a quaternion [w, x, y, z], as body orientations are written) and the friction.
SwingTwistJointDef read_swing_twist(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  SwingTwistJointDef def;
  read_frames(fields, bodies, def);
  {
    ObjectReader f(fields.source(), fields.object("cone"), fields.path_of("cone"));
    def.cone.enabled = f.boolean("enabled", def.cone.enabled);
    def.cone.half_angle_x = f.number("half_angle_x", def.cone.half_angle_x);
    def.cone.half_angle_y = f.number("half_angle_y", def.cone.half_angle_y);
    f.no_other_keys();
  }
  def.twist = read_limit(fields, "twist");
  {
    ObjectReader f(fields.source(), fields.object("spring"), fields.path_of("spring"));
    def.spring.spring = f.spring("spring", def.spring.spring);
    def.spring.target = f.quaternion("target", def.spring.target);
    f.no_other_keys();
  }
  {
    ObjectReader f(fields.source(), fields.object("motor"), fields.path_of("motor"));
    def.motor.enabled = f.boolean("enabled", def.motor.enabled);
    def.motor.max_torque = f.number("max_torque", def.motor.max_torque);
    f.no_other_keys();
  }
  fields.no_other_keys();
  return def;
}

WheelJointDef read_wheel(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  WheelJointDef def;
  read_frames(fields, bodies, def);
  def.spring = read_axis_spring(fields);
  def.sprung_mass = fields.number("sprung_mass", def.sprung_mass);
  def.limit = read_limit(fields);
  def.motor = read_motor(fields, "max_torque", &AngularMotor::max_torque);
  def.steering = fields.number("steering", def.steering);
  fields.no_other_keys();
  return def;
}

void write_swing_twist(const World& world, JointId id, const BodyIndex& index,
                       nlohmann::json& out) {
  const auto def = world.joint_def<SwingTwistJointDef>(id);
  write_frames(def, index, out);
  out["cone"] = {{"enabled", def.cone.enabled},
                 {"half_angle_x", def.cone.half_angle_x},
                 {"half_angle_y", def.cone.half_angle_y}};
  out["twist"] = limit_json(def.twist);
  const Quaternion& q = def.spring.target;
  out["spring"] = {{"spring", spring_json(def.spring.spring)},
                   {"target", {q.w(), q.x(), q.y(), q.z()}}};
  out["motor"] = {{"enabled", def.motor.enabled}, {"max_torque", def.motor.max_torque}};
}

void write_wheel(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out) {
  const auto def = world.joint_def<WheelJointDef>(id);
  write_frames(def, index, out);
  out["spring"] = axis_spring_json(def.spring);
  out["sprung_mass"] = def.sprung_mass;
  out["limit"] = limit_json(def.limit);
  out["motor"] = motor_json(def.motor, "max_torque", &AngularMotor::max_torque);
  out["steering"] = def.steering;
}

MotorJointDef read_motor_joint(ObjectReader& fields, const std::vector<BodyId>& bodies) {
  MotorJointDef def;
  read_frames(fields, bodies, def);
  def.max_force = fields.number("max_force", def.max_force);
  def.max_torque = fields.number("max_torque", def.max_torque);
  def.linear = fields.spring("linear", def.linear);
  def.angular = fields.spring("angular", def.angular);
  fields.no_other_keys();
  return def;
}

void write_motor_joint(const World& world, JointId id, const BodyIndex& index,
                       nlohmann::json& out) {
  const auto def = world.joint_def<MotorJointDef>(id);
  write_frames(def, index, out);
  out["max_force"] = def.max_force;
  out["max_torque"] = def.max_torque;
  out["linear"] = spring_json(def.linear);
  out["angular"] = spring_json(def.angular);
}

// Creates a joint, or changes one in place, from a Def read by ReadDef.
template <class Def, Def (*ReadDef)(ObjectReader&, const std::vector<BodyId>&)>
JointId create_from(World& world, ObjectReader& fields, const std::vector<BodyId>& bodies) {
  const Def def = ReadDef(fields, bodies);
  return fields.call([&] { return world.create_joint(def); });
}

template <class Def, Def (*ReadDef)(ObjectReader&, const std::vector<BodyId>&)>
void set_from(World& world, JointId id, ObjectReader& fields, const std::vector<BodyId>& bodies) {
  const Def def = ReadDef(fields, bodies);
  fields.call([&] { world.set_joint(id, def); });
}

#define SOFTSTEP_JOINT_FORMAT(NAME, TYPE, DEF, READ, WRITE) \
  {NAME, TYPE, create_from<DEF, READ>, WRITE, set_from<DEF, READ>}

constexpr JointFormat kJointFormats[] = {
    SOFTSTEP_JOINT_FORMAT("ball", JointType::Ball, BallJointDef, read_ball, write_ball),
    SOFTSTEP_JOINT_FORMAT("distance", JointType::Distance, DistanceJointDef, read_distance, write_distance),
    SOFTSTEP_JOINT_FORMAT("revolute", JointType::Revolute, RevoluteJointDef, read_revolute, write_revolute),
    SOFTSTEP_JOINT_FORMAT("prismatic", JointType::Prismatic, PrismaticJointDef, read_prismatic, write_prismatic),
    SOFTSTEP_JOINT_FORMAT("weld", JointType::Weld, WeldJointDef, read_weld, write_weld),
    SOFTSTEP_JOINT_FORMAT("swing_twist", JointType::SwingTwist, SwingTwistJointDef, read_swing_twist, write_swing_twist),
    SOFTSTEP_JOINT_FORMAT("wheel", JointType::Wheel, WheelJointDef, read_wheel, write_wheel),
    SOFTSTEP_JOINT_FORMAT("motor", JointType::Motor, MotorJointDef, read_motor_joint, write_motor_joint),
};

#undef SOFTSTEP_JOINT_FORMAT

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
