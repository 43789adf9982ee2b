// The public World: validation first, then the change. Nothing is modified before every
// check of a call has passed.
#include "softstep/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "joints/joint_common.hpp"
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
  if (!simd_width_built(requested)) {
    validation::reject(call, "WorldSettings.simd", simd_width_name(requested),
                       "this build left the width out (CMake option SOFTSTEP_WIDTHS)");
  }
  if (!simd_width_supported(requested)) {
    validation::reject(call, "WorldSettings.simd", simd_width_name(requested),
                       "this CPU lacks " + simd_width_requirement(requested));
  }
  return requested;
}

}  // namespace

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::Ball:
      return "ball";
    case JointType::Distance:
      return "distance";
    case JointType::Revolute:
      return "revolute";
    case JointType::Prismatic:
      return "prismatic";
    case JointType::Weld:
      return "weld";
    case JointType::SwingTwist:
      return "swing_twist";
    case JointType::Wheel:
      return "wheel";
    case JointType::Motor:
      return "motor";
  }
  return "?";
}

// ---- lookups that reject unknown ids ------------------------------------------------------

std::uint32_t body_slot(const World::Impl& w, std::string_view call, std::string_view field,
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

std::uint32_t joint_slot(const World::Impl& w, std::string_view call, JointId id) {
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
static std::uint32_t take_slot(PagedVector<Slot>& slots, std::vector<std::uint32_t>& free_list) {
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
  ++bodies_version;
  plan_built = false;
}

// ---- construction and settings ------------------------------------------------------------

World::World(const WorldSettings& settings) : impl_(std::make_unique<Impl>()) {
  validation::settings("World", settings);
  impl_->width = resolve_width("World", settings.simd);
  impl_->settings = settings;
  impl_->lane_solver = make_lane_solver(impl_->width);
  impl_->contact_solver = make_contact_solver(impl_->width);
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
    w.contact_solver = make_contact_solver(width);
    w.width = width;
  }
  w.settings = settings;
  if (!settings.sleeping) w.wake_all();
  w.content_changed();
  if (w.recorder) w.recorder->set_settings(settings);
}

void World::reserve(std::size_t bodies, std::size_t joints) {
  constexpr std::size_t kMaxSlots = 0xFFFFFFFEu;  // 0xFFFFFFFF is the id of nothing
  if (bodies > kMaxSlots) {
    validation::reject("reserve", "bodies", std::to_string(bodies), "must be <= 4294967294");
  }
  if (joints > kMaxSlots) {
    validation::reject("reserve", "joints", std::to_string(joints), "must be <= 4294967294");
  }
  impl_->bodies.reserve(bodies);
  impl_->joints.reserve(joints);
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
  b.force.setZero();
  b.torque.setZero();
  b.joints.clear();
  b.never_sleep = def.never_sleep;
  b.user_data = def.user_data;
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
  // Its contacts' warm-start entries go with it now, not at the next step: the state hash and
  // a scene file saved before that step would name a dead body. (A pass over the cache: a
  // world that destroys bodies by the thousand between steps may want a per-body index.)
  if (!w.contact_cache.empty()) {
    w.settle_contact_readings();
    w.contact_cache.erase_body(body_word(id));
  }
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
          b.never_sleep, b.force, b.torque};
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
    validation::linear_speed(call, "velocity", velocity, velocity, w.settings.max_linear_speed);
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
  check_point_levers(*impl_, "set_mass_properties", "inertia", slot, mass, inertia);
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
  validation::linear_speed("apply_impulse", "impulse", impulse, v, w.settings.max_linear_speed);
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
// The lifecycle every type shares; what a type is lives in its kind (joints/*_joint.cpp).

JointId add_joint(World::Impl& w, JointSlot&& joint) {
  const std::uint32_t slot = take_slot(w.joints, w.free_joints);
  // A joint to a sleeping island wakes it (one end may be awake and moving).
  w.touch(joint.body_a);
  w.touch(joint.body_b);
  w.unpack_joints();
  joint.generation = w.joints[slot].generation;
  joint.alive = true;
  joint.impulse.fill(0.0f);
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

void record_created_joint(const World& world, World::Impl& w, JointId id) {
  if (w.recorder) w.recorder->create_joint(world, id);
}

void record_set_joint(const World& world, World::Impl& w, JointId id) {
  if (w.recorder) w.recorder->set_joint(world, id);
}

void replace_joint(World::Impl& w, std::uint32_t slot, JointSlot&& joint) {
  JointSlot& j = w.joints[slot];
  w.touch(j.body_a);
  w.touch(j.body_b);
  joint.generation = j.generation;
  joint.alive = true;
  joint.angle = j.angle;
  const bool packed = w.joints_packed && w.lane_solver->in_lanes(slot);
  joint.impulse = w.joint_impulses(slot);
  j = std::move(joint);
  // Same kernel and signature: only this lane changes. Otherwise the world re-packs.
  if (!packed || !w.lane_solver->refresh(slot, w.joints, w.settings.specialize)) {
    w.unpack_joints();
  }
  w.plan_built = false;
}

const JointSlot& joint_of_type(const World::Impl& w, std::string_view call, JointId id,
                               JointType type) {
  const JointSlot& j = w.joints[joint_slot(w, call, id)];
  if (j.type != type) {
    validation::reject(call, "joint", std::string("a ") + joint_type_name(j.type) + " joint",
                       std::string("is not a ") + joint_type_name(type) + " joint");
  }
  return j;
}

void World::destroy_joint(JointId id) {
  Impl& w = *impl_;
  const std::uint32_t slot = joint_slot(w, "destroy_joint", id);
  JointSlot& j = w.joints[slot];
  w.touch(j.body_a);
  w.touch(j.body_b);
  // Proportional to what changed: the other joints keep their lanes (issue 17: unpacking
  // cost 3.3 ms at 100,000 joints, and the next step re-packed them all).
  if (!w.joints_packed || !w.lane_solver->vacate(slot)) w.unpack_joints();
  w.plan_built = false;
  for (std::uint32_t body : {j.body_a, j.body_b}) {
    auto& list = w.bodies[body].joints;
    list.erase(std::find(list.begin(), list.end(), slot));
  }
  w.coloring.remove(slot);
  j.alive = false;
  ++j.generation;
  j.impulse.fill(0.0f);
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
  const std::array<float, kMaxJointImpulses> impulse = w.joint_impulses(id.index);
  JointReading r;
  JointKinds::with(j.type, [&]<class Kind>() { Kind::reading(w, j, impulse.data(), r); });
  if (w.last_substep > 0.0) {
    r.force = r.impulse / w.last_substep;
    r.torque = r.angular_impulse / w.last_substep;
  }
  return r;
}

}  // namespace softstep
