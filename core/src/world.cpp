// The public World: validation first, then the change. Nothing is modified before every
// check of a call has passed.
#include "softstep/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "recording/recorder.hpp"
#include "validation.hpp"
#include "world_impl.hpp"

namespace softstep {

namespace {

const char* type_name(BodyType t) {
  return t == BodyType::Static ? "static" : t == BodyType::Kinematic ? "kinematic" : "dynamic";
}

SimdWidth resolve_width(std::string_view call, SimdWidth requested) {
  if (requested == SimdWidth::Best) return best_simd_width();
  if (!simd_width_supported(requested)) {
    validation::reject(call, "WorldSettings.simd", simd_width_name(requested),
                       "this CPU lacks that instruction set (or FMA, which this build uses)");
  }
  return requested;
}

}  // namespace

// ---- lookups that reject unknown ids ------------------------------------------------------

static std::uint32_t body_slot(const World::Impl& w, std::string_view call, std::string_view field,
                               BodyId id) {
  if (id.index >= w.bodies.size() || !w.bodies[id.index].alive ||
      w.bodies[id.index].generation != id.generation) {
    validation::reject(
        call, field,
        "BodyId{" + std::to_string(id.index) + ", gen " + std::to_string(id.generation) + "}",
        "no such body (never created, or destroyed)");
  }
  return id.index;
}

static std::uint32_t joint_slot(const World::Impl& w, std::string_view call, JointId id) {
  if (id.index >= w.joints.size() || !w.joints[id.index].alive ||
      w.joints[id.index].generation != id.generation) {
    validation::reject(
        call, "joint",
        "JointId{" + std::to_string(id.index) + ", gen " + std::to_string(id.generation) + "}",
        "no such joint (never created, or destroyed)");
  }
  return id.index;
}

// ---- Impl helpers -------------------------------------------------------------------------

// Reuses the most recently freed slot (its generation was bumped when it was freed), or
// appends one: the ids handed out depend only on the sequence of calls.
template <class Slot>
static std::uint32_t take_slot(std::vector<Slot>& slots, std::vector<std::uint32_t>& free_list) {
  if (!free_list.empty()) {
    const std::uint32_t slot = free_list.back();
    free_list.pop_back();
    return slot;
  }
  slots.emplace_back();
  return static_cast<std::uint32_t>(slots.size() - 1);
}

void World::Impl::unpack_joints() {
  if (joints_packed && lane_solver) lane_solver->save_impulses(joints);
  joints_packed = false;
  plan_built = false;
}

void World::Impl::content_changed() {
  bodies_listed = false;
  plan_built = false;
}

// ---- construction and settings ------------------------------------------------------------

World::World(const WorldSettings& settings) : impl_(std::make_unique<Impl>()) {
  validation::settings("World", settings);
  impl_->width = resolve_width("World", settings.simd);
  impl_->settings = settings;
  impl_->lane_solver = make_lane_solver(impl_->width);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const WorldSettings& World::settings() const {
  return impl_->settings;
}

void World::set_settings(const WorldSettings& settings) {
  validation::settings("set_settings", settings);
  const SimdWidth width = resolve_width("set_settings", settings.simd);
  Impl& w = *impl_;
  // A kinematic body keeps the velocity it was given, so a lower limit cannot clamp it.
  for (const BodySlot& b : w.bodies) {
    if (b.alive && b.type == BodyType::Kinematic &&
        b.linear_velocity.norm() > settings.max_linear_speed) {
      validation::reject("set_settings", "WorldSettings.max_linear_speed",
                         validation::format(settings.max_linear_speed),
                         "a kinematic body moves at " +
                             validation::format(b.linear_velocity.norm()) + " m/s; slow it first");
    }
  }
  if (width != w.width || settings.specialize != w.settings.specialize) w.unpack_joints();
  if (width != w.width) {
    w.lane_solver = make_lane_solver(width);
    w.width = width;
  }
  w.settings = settings;
  if (!settings.sleeping) w.wake_all();
  w.content_changed();
  if (w.recorder) w.recorder->set_settings(settings);
}

// ---- bodies -------------------------------------------------------------------------------

BodyId World::create_body(const BodyDef& def) {
  validation::body_def("create_body", def, impl_->settings.max_linear_speed);
  Impl& w = *impl_;
  const std::uint32_t slot = take_slot(w.bodies, w.free_bodies);
  BodySlot& b = w.bodies[slot];
  b.alive = true;
  b.type = def.type;
  b.position = def.position;
  b.orientation = def.orientation.normalized();
  b.linear_velocity = def.linear_velocity;
  b.angular_velocity = def.angular_velocity;
  const bool dynamic = def.type == BodyType::Dynamic;
  b.mass = dynamic ? def.mass : 0.0;
  b.inertia = dynamic ? def.inertia : Eigen::Matrix3d::Zero();
  b.inverse_inertia = dynamic ? Eigen::Matrix3d(def.inertia.inverse()) : Eigen::Matrix3d::Zero();
  b.diagonal_inertia = b.inertia.isDiagonal(0.0);
  b.gravity_scale = def.gravity_scale;
  b.linear_damping = def.linear_damping;
  b.angular_damping = def.angular_damping;
  b.joints.clear();
  b.never_sleep = def.never_sleep;
  b.asleep = false;
  b.sleep_time = 0.0;
  ++w.body_count;
  w.content_changed();
  if (w.recorder) w.recorder->create_body(def, {slot, b.generation});
  return {slot, b.generation};
}

void World::destroy_body(BodyId id) {
  Impl& w = *impl_;
  const std::uint32_t slot = body_slot(w, "destroy_body", "body", id);
  w.touch(slot);  // the rest of its island may have leant on it
  const std::vector<std::uint32_t> attached = w.bodies[slot].joints;
  for (std::uint32_t j : attached) destroy_joint({j, w.joints[j].generation});
  BodySlot& b = w.bodies[slot];
  b.alive = false;
  ++b.generation;
  b.joints.clear();
  w.free_bodies.push_back(slot);
  --w.body_count;
  w.content_changed();
  if (w.recorder) w.recorder->destroy_body(id);
}

bool World::is_valid(BodyId id) const {
  const Impl& w = *impl_;
  return id.index < w.bodies.size() && w.bodies[id.index].alive &&
         w.bodies[id.index].generation == id.generation;
}

BodyState World::body(BodyId id) const {
  const BodySlot& b = impl_->bodies[body_slot(*impl_, "body", "body", id)];
  return {b.type, b.position, b.orientation,   b.linear_velocity, b.angular_velocity,
          b.mass, b.inertia,  b.gravity_scale, b.linear_damping,  b.angular_damping,
          b.never_sleep};
}

void World::set_position(BodyId id, const Eigen::Vector3d& position) {
  const std::uint32_t slot = body_slot(*impl_, "set_position", "body", id);
  validation::finite("set_position", "position", position);
  impl_->touch(slot);
  impl_->bodies[slot].position = position;
  if (impl_->recorder) impl_->recorder->set_vector(recording::Tag::SetPosition, id, position);
}

void World::set_orientation(BodyId id, const Quaternion& orientation) {
  const std::uint32_t slot = body_slot(*impl_, "set_orientation", "body", id);
  const Quaternion q = validation::unit_quaternion("set_orientation", "orientation", orientation);
  impl_->touch(slot);
  impl_->bodies[slot].orientation = q;
  if (impl_->recorder) impl_->recorder->set_orientation(id, orientation);
}

namespace {
void set_velocity(World::Impl& w, std::string_view call, BodyId id, const Eigen::Vector3d& velocity,
                  Eigen::Vector3d BodySlot::*member) {
  const std::uint32_t slot = body_slot(w, call, "body", id);
  validation::finite(call, "velocity", velocity);
  if (member == &BodySlot::linear_velocity) {
    validation::linear_speed(call, "velocity", validation::format(velocity), velocity,
                             w.settings.max_linear_speed);
  }
  if (w.bodies[slot].type == BodyType::Static && !velocity.isZero(0.0)) {
    validation::reject(call, "velocity", validation::format(velocity),
                       "a static body cannot move (use a kinematic body)");
  }
  w.touch(slot);
  w.bodies[slot].*member = velocity;
}
}  // namespace

void World::set_linear_velocity(BodyId id, const Eigen::Vector3d& velocity) {
  set_velocity(*impl_, "set_linear_velocity", id, velocity, &BodySlot::linear_velocity);
  if (impl_->recorder) impl_->recorder->set_vector(recording::Tag::SetLinearVelocity, id, velocity);
}

void World::set_angular_velocity(BodyId id, const Eigen::Vector3d& velocity) {
  set_velocity(*impl_, "set_angular_velocity", id, velocity, &BodySlot::angular_velocity);
  if (impl_->recorder)
    impl_->recorder->set_vector(recording::Tag::SetAngularVelocity, id, velocity);
}

void World::set_mass_properties(BodyId id, double mass, const Eigen::Matrix3d& inertia) {
  const std::uint32_t slot = body_slot(*impl_, "set_mass_properties", "body", id);
  BodySlot& b = impl_->bodies[slot];
  if (b.type != BodyType::Dynamic) {
    validation::reject("set_mass_properties", "body", type_name(b.type),
                       "only a dynamic body has mass properties");
  }
  validation::dynamic_mass("set_mass_properties", "mass", mass);
  validation::inertia_tensor("set_mass_properties", "inertia", inertia);
  impl_->touch(slot);
  b.mass = mass;
  b.inertia = inertia;
  b.inverse_inertia = inertia.inverse();
  b.diagonal_inertia = inertia.isDiagonal(0.0);
  if (impl_->recorder) impl_->recorder->set_mass_properties(id, mass, inertia);
}

void World::apply_impulse(BodyId id, const Eigen::Vector3d& impulse,
                          const Eigen::Vector3d& world_point) {
  Impl& w = *impl_;
  const std::uint32_t slot = body_slot(w, "apply_impulse", "body", id);
  if (w.bodies[slot].type != BodyType::Dynamic) {
    validation::reject("apply_impulse", "body", type_name(w.bodies[slot].type),
                       "only a dynamic body responds to an impulse");
  }
  validation::finite("apply_impulse", "impulse", impulse);
  validation::finite("apply_impulse", "world_point", world_point);
  BodySlot& b = w.bodies[slot];
  const Eigen::Matrix3d r = b.orientation.toRotationMatrix();
  const Eigen::Vector3d v = b.linear_velocity + impulse / b.mass;
  const Eigen::Vector3d omega =
      b.angular_velocity +
      r * (b.inverse_inertia * (r.transpose() * (world_point - b.position).cross(impulse)));
  // The same bounds as a velocity set directly.
  if (!omega.allFinite() || omega.cwiseAbs().maxCoeff() > validation::kMaxMagnitude) {
    validation::reject("apply_impulse", "impulse", validation::format(impulse),
                       "gives the body an angular velocity beyond +-" +
                           validation::format(validation::kMaxMagnitude) + " rad/s");
  }
  validation::linear_speed("apply_impulse", "impulse", validation::format(impulse), v,
                           w.settings.max_linear_speed);
  w.touch(slot);
  b.linear_velocity = v;
  b.angular_velocity = omega;
  if (w.recorder) w.recorder->apply_impulse(id, impulse, world_point);
}

bool World::is_awake(BodyId id) const {
  const BodySlot& b = impl_->bodies[body_slot(*impl_, "is_awake", "body", id)];
  return b.type != BodyType::Static && !b.asleep;
}

std::size_t World::body_count() const {
  return impl_->body_count;
}

Eigen::Vector3d World::local_point(BodyId id, const Eigen::Vector3d& world_point) const {
  const BodySlot& b = impl_->bodies[body_slot(*impl_, "local_point", "body", id)];
  validation::finite("local_point", "world_point", world_point);
  return b.orientation.conjugate() * (world_point - b.position);
}

// ---- joints -------------------------------------------------------------------------------

namespace {

struct JointEnds {
  std::uint32_t a, b;
};

JointEnds check_joint_ends(const World::Impl& w, std::string_view call, BodyId a, BodyId b,
                           const Eigen::Vector3d& anchor_a, const Eigen::Vector3d& anchor_b,
                           const Spring& spring, std::string_view def) {
  const std::string prefix(def);
  const std::uint32_t slot_a = body_slot(w, call, prefix + ".body_a", a);
  const std::uint32_t slot_b = body_slot(w, call, prefix + ".body_b", b);
  if (slot_a == slot_b) {
    validation::reject(call, prefix + ".body_b", "BodyId{" + std::to_string(b.index) + "}",
                       "a joint needs two different bodies (body_a is the same body)");
  }
  validation::finite(call, prefix + ".local_anchor_a", anchor_a);
  validation::finite(call, prefix + ".local_anchor_b", anchor_b);
  validation::spring(call, prefix + ".spring", spring);
  return {slot_a, slot_b};
}

}  // namespace

static JointId add_joint(World::Impl& w, JointSlot&& joint) {
  const std::uint32_t slot = take_slot(w.joints, w.free_joints);
  // A joint to a sleeping island wakes it (one end may be awake and moving).
  w.touch(joint.body_a);
  w.touch(joint.body_b);
  w.unpack_joints();
  joint.generation = w.joints[slot].generation;
  joint.alive = true;
  joint.impulse.setZero();
  w.joints[slot] = std::move(joint);
  w.joints_without_history = true;
  const JointSlot& j = w.joints[slot];
  w.bodies[j.body_a].joints.push_back(slot);
  w.bodies[j.body_b].joints.push_back(slot);
  // Only dynamic bodies are written by the solver, so only they block a colour.
  const auto blocking = [&](std::uint32_t body) {
    return w.bodies[body].type == BodyType::Dynamic ? body : graph_coloring::kNonBlocking;
  };
  w.coloring.add(slot, blocking(j.body_a), blocking(j.body_b));
  ++w.joint_count;
  return {slot, j.generation};
}

// Reports a created joint to a running recording.
static JointId recorded(const World& world, World::Impl& w, JointId id) {
  if (w.recorder) w.recorder->create_joint(world, id);
  return id;
}

JointId World::create_ball_joint(const BallJointDef& def) {
  Impl& w = *impl_;
  const JointEnds ends =
      check_joint_ends(w, "create_ball_joint", def.body_a, def.body_b, def.local_anchor_a,
                       def.local_anchor_b, def.spring, "BallJointDef");
  JointSlot j;
  j.type = JointType::Ball;
  j.body_a = ends.a;
  j.body_b = ends.b;
  j.local_anchor_a = def.local_anchor_a;
  j.local_anchor_b = def.local_anchor_b;
  j.spring = def.spring;
  return recorded(*this, w, add_joint(w, std::move(j)));
}

JointId World::create_distance_joint(const DistanceJointDef& def) {
  Impl& w = *impl_;
  const char* call = "create_distance_joint";
  const JointEnds ends = check_joint_ends(w, call, def.body_a, def.body_b, def.local_anchor_a,
                                          def.local_anchor_b, def.spring, "DistanceJointDef");
  validation::non_negative(call, "DistanceJointDef.rest_length", def.rest_length);
  validation::non_negative(call, "DistanceJointDef.min_length", def.min_length);
  if (std::isnan(def.max_length) || def.max_length < def.min_length ||
      (def.max_length > validation::kMaxMagnitude &&
       def.max_length != std::numeric_limits<double>::infinity())) {
    validation::reject(call, "DistanceJointDef.max_length", validation::format(def.max_length),
                       "must be >= min_length (" + validation::format(def.min_length) +
                           ") and <= " + validation::format(validation::kMaxMagnitude) +
                           "; +infinity for no upper limit");
  }
  JointSlot j;
  j.type = JointType::Distance;
  j.body_a = ends.a;
  j.body_b = ends.b;
  j.local_anchor_a = def.local_anchor_a;
  j.local_anchor_b = def.local_anchor_b;
  j.spring = def.spring;
  j.min_length = def.min_length;
  j.max_length = def.max_length;
  j.rest_length = std::clamp(def.rest_length, def.min_length, def.max_length);
  return recorded(*this, w, add_joint(w, std::move(j)));
}

void World::destroy_joint(JointId id) {
  Impl& w = *impl_;
  const std::uint32_t slot = joint_slot(w, "destroy_joint", id);
  JointSlot& j = w.joints[slot];
  w.touch(j.body_a);
  w.touch(j.body_b);
  w.unpack_joints();
  for (std::uint32_t body : {j.body_a, j.body_b}) {
    auto& list = w.bodies[body].joints;
    list.erase(std::find(list.begin(), list.end(), slot));
  }
  w.coloring.remove(slot);
  j.alive = false;
  ++j.generation;
  j.impulse.setZero();
  w.free_joints.push_back(slot);
  --w.joint_count;
  if (w.recorder) w.recorder->destroy_joint(id);
}

bool World::is_valid(JointId id) const {
  const Impl& w = *impl_;
  return id.index < w.joints.size() && w.joints[id.index].alive &&
         w.joints[id.index].generation == id.generation;
}

JointType World::joint_type(JointId id) const {
  return impl_->joints[joint_slot(*impl_, "joint_type", id)].type;
}

std::size_t World::joint_count() const {
  return impl_->joint_count;
}

JointReading World::joint_reading(JointId id) const {
  const Impl& w = *impl_;
  const JointSlot& j = w.joints[joint_slot(w, "joint_reading", id)];
  const BodySlot& a = w.bodies[j.body_a];
  const BodySlot& b = w.bodies[j.body_b];
  const Eigen::Vector3d anchor_a = a.position + a.orientation * j.local_anchor_a;
  const Eigen::Vector3d anchor_b = b.position + b.orientation * j.local_anchor_b;
  const Eigen::Vector3d d = anchor_b - anchor_a;
  const Eigen::Vector3f stored = w.joints_packed && w.lane_solver->in_lanes(id.index)
                                     ? w.lane_solver->impulse(id.index)
                                     : j.impulse;
  JointReading r;
  if (j.type == JointType::Ball) {
    r.impulse = stored.cast<double>();
    r.error = d.norm();
  } else {
    const double length = d.norm();
    const Eigen::Vector3d n = length > 1e-9 ? Eigen::Vector3d(d / length) : Eigen::Vector3d::Zero();
    r.impulse = double(stored.x() + stored.y() - stored.z()) * n;
    if (j.spring.is_free()) {
      r.error = std::max({0.0, j.min_length - length, length - j.max_length});
    } else {
      r.error = std::abs(length - j.rest_length);
    }
  }
  r.force =
      w.last_substep > 0.0 ? Eigen::Vector3d(r.impulse / w.last_substep) : Eigen::Vector3d::Zero();
  return r;
}

namespace {
template <class Def>
Def joint_ends(const World::Impl& w, const JointSlot& j) {
  Def def;
  def.body_a = {j.body_a, w.bodies[j.body_a].generation};
  def.body_b = {j.body_b, w.bodies[j.body_b].generation};
  def.local_anchor_a = j.local_anchor_a;
  def.local_anchor_b = j.local_anchor_b;
  def.spring = j.spring;
  return def;
}

const JointSlot& joint_of_type(const World::Impl& w, const char* call, JointId id, JointType type) {
  const JointSlot& j = w.joints[joint_slot(w, call, id)];
  if (j.type != type) {
    validation::reject(call, "joint", type == JointType::Ball ? "a distance joint" : "a ball joint",
                       "is not of the type asked for");
  }
  return j;
}
}  // namespace

BallJointDef World::ball_joint(JointId id) const {
  return joint_ends<BallJointDef>(*impl_, joint_of_type(*impl_, "ball_joint", id, JointType::Ball));
}

DistanceJointDef World::distance_joint(JointId id) const {
  const JointSlot& j = joint_of_type(*impl_, "distance_joint", id, JointType::Distance);
  DistanceJointDef def = joint_ends<DistanceJointDef>(*impl_, j);
  def.rest_length = j.rest_length;
  def.min_length = j.min_length;
  def.max_length = j.max_length;
  return def;
}

}  // namespace softstep
