// The world: bodies, joints and the Soft Step solver. Not thread-safe: one thread calls it
// at a time; step() itself uses WorldSettings::threads threads (OpenMP, or the host's job
// system through set_task_callbacks), with results that do not depend on how many.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "softstep/body.hpp"
#include "softstep/contacts.hpp"
#include "softstep/errors.hpp"
#include "softstep/ids.hpp"
#include "softstep/joints.hpp"
#include "softstep/joints/prismatic.hpp"
#include "softstep/joints/revolute.hpp"
#include "softstep/joints/swing_twist.hpp"
#include "softstep/joints/weld.hpp"
#include "softstep/joints/wheel.hpp"
#include "softstep/joints/motor.hpp"
#include "softstep/profile.hpp"
#include "softstep/step_plan.hpp"
#include "softstep/task_callbacks.hpp"
#include "softstep/world_settings.hpp"

namespace softstep {

// A body as it is now.
struct BodyState {
  BodyType type;
  Eigen::Vector3d position;
  Quaternion orientation;
  Eigen::Vector3d linear_velocity;
  Eigen::Vector3d angular_velocity;
  double mass;              // kg (0 for static and kinematic)
  Eigen::Matrix3d inertia;  // body frame, kg m^2
  double gravity_scale;
  double linear_damping;
  double angular_damping;
  bool never_sleep;
  // What apply_force and apply_torque gathered for the next step (world frame): the force, N,
  // and the torque, N m, the forces' moments about the centre included.
  Eigen::Vector3d force;
  Eigen::Vector3d torque;
};

// How the solver has laid out the joints (see graph_coloring/).
struct SolverLayout {
  SimdWidth simd;  // width in use (never Best)
  int lanes;       // 1, 4 or 8
  int colors_used;
  std::vector<std::uint32_t> joints_per_color;
  std::uint32_t overflow_joints;
  double lane_fill;  // real joints / lanes in coloured groups
};

// The first sub-step of the last step as the solver saw it, recorded while
// World::set_solve_capture is on. It is what the accuracy references (reference.hpp) need to
// rebuild exactly the soft system that sub-step's Gauss-Seidel solve approximated and to
// measure how far the solve landed from its exact solution. Body vectors are indexed by body
// slot (BodyId::index); static bodies and free slots hold zeros.
struct SolveCapture {
  double h = 0.0;            // the sub-step, s
  double rigid_hertz = 0.0;  // frequency rigid rows were solved with: min(rigid_hertz, 1/(4 h))
  std::vector<Eigen::Vector3d> position;  // at the step start, m
  std::vector<Quaternion> orientation;    // at the step start
  // Velocities (linear then angular, world frame) after gravity and damping, before the warm
  // start, and after the last solve pass of the first sub-step (before positions move).
  std::vector<Vector6> velocity_before_solve;
  std::vector<Vector6> velocity_after_solve;
  // The masses the solver used (with the geometric-stiffness inertia, if on).
  std::vector<double> inverse_mass;              // 1/kg
  std::vector<Eigen::Matrix3d> inverse_inertia;  // world frame, 1/(kg m^2)
  // Every joint alive during the step and its accumulated impulse after the solve, N s
  // (ball: world-frame vector; distance: x spring or rod row, y lower and z upper limit).
  std::vector<JointId> joints;
  std::vector<Eigen::Vector3d> impulse;
};

class World {
 public:
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const WorldSettings& settings() const;
  void set_settings(const WorldSettings& settings);
  // Steps on more than one thread run their workers through these callbacks instead of
  // OpenMP (see task_callbacks.hpp for what the host must guarantee); both nullptr: OpenMP
  // again. Rejected when only one of enqueue and finish is given.
  void set_task_callbacks(const TaskCallbacks& callbacks);

  // Room for this many bodies and joints in all, made at once: creating them then moves no
  // storage (a world grown body by body copies its slots each time they double). Changes
  // nothing else; at most 2^32 - 2 of each.
  void reserve(std::size_t bodies, std::size_t joints);

  BodyId create_body(const BodyDef& def);
  // Destroys the body and every joint attached to it.
  void destroy_body(BodyId id);
  bool is_valid(BodyId id) const;
  BodyState body(BodyId id) const;
  void set_position(BodyId id, const Eigen::Vector3d& position);
  void set_orientation(BodyId id, const Quaternion& orientation);
  void set_linear_velocity(BodyId id, const Eigen::Vector3d& velocity);
  void set_angular_velocity(BodyId id, const Eigen::Vector3d& velocity);
  void set_mass_properties(BodyId id, double mass, const Eigen::Matrix3d& inertia);
  // Adds impulse (N s, world frame) at world_point to a dynamic body's velocities.
  void apply_impulse(BodyId id, const Eigen::Vector3d& impulse, const Eigen::Vector3d& world_point);
  // Adds a force (N, world frame) acting at world_point to a dynamic body for the next step:
  // applied in each of its sub-steps (with the torque (world_point - centre) x force), then
  // cleared. Forces and torques given before a step add up. Wakes the body's island. A scene
  // with none pays nothing: the plan runs the Forces stage only while some body has one.
  void apply_force(BodyId id, const Eigen::Vector3d& force, const Eigen::Vector3d& world_point);
  // Adds a torque (N m, world frame) to a dynamic body for the next step, as apply_force.
  void apply_torque(BodyId id, const Eigen::Vector3d& torque);
  // False while the body's island sleeps (static bodies: always false). Setting a velocity,
  // a pose or the mass, applying an impulse, a force or a torque, or adding or removing a joint
  // on the body wakes its island.
  bool is_awake(BodyId id) const;
  std::size_t body_count() const;

  // Any joint type: BallJointDef, DistanceJointDef, RevoluteJointDef, PrismaticJointDef,
  // WeldJointDef, SwingTwistJointDef, WheelJointDef, MotorJointDef. Every field is validated
  // first (InvalidArgument names it); the joint wakes the islands of both bodies.
  template <class Def>
  JointId create_joint(const Def& def);
  // The joint's definition as the world holds it (normalized axes, clamped lengths).
  // Throws InvalidArgument when the joint is of another type.
  template <class Def>
  Def joint_def(JointId id) const;
  // Changes a joint in place, keeping its id and its warm-start impulses: springs, limits,
  // motors, anchors and frames. The bodies must stay the same. Validated like create_joint;
  // wakes the island. A change that keeps the joint's features (a motor's speed, a spring's
  // target) refreshes its lane without re-packing the world.
  template <class Def>
  void set_joint(JointId id, const Def& def);

  JointId create_ball_joint(const BallJointDef& def);          // = create_joint(def)
  JointId create_distance_joint(const DistanceJointDef& def);  // = create_joint(def)
  void destroy_joint(JointId id);
  bool is_valid(JointId id) const;
  JointType joint_type(JointId id) const;
  JointReading joint_reading(JointId id) const;
  std::size_t joint_count() const;

  // Every live body or joint in slot order (the ids create_* returned): to walk the world,
  // e.g. to copy poses into an engine's objects. Allocates the vector each call.
  std::vector<BodyId> body_ids() const;
  std::vector<JointId> joint_ids() const;
  // The caller's own value per body or joint: an integer, or a pointer as std::uintptr_t. Never
  // read, validated or hashed by softstep (setting it changes nothing the world simulates and
  // not state_hash); 0 until set, a body's from BodyDef::user_data. Unknown ids are rejected.
  void set_user_data(BodyId id, std::uint64_t value);
  std::uint64_t user_data(BodyId id) const;
  void set_user_data(JointId id, std::uint64_t value);
  std::uint64_t user_data(JointId id) const;

  // Advances the world by dt seconds (> 0, finite) in settings().substeps sub-steps.
  void step(double dt);
  // The same with this step's contacts from the caller's collision detection (contacts.hpp
  // says why they are an argument, and the conventions). The span is read during the call
  // only. Every manifold is validated before anything changes (InvalidArgument names the
  // field, e.g. "contacts[3].normal"). A manifold between a sleeping body and an awake dynamic
  // one wakes the sleeper; one whose bodies are all static or asleep is not solved and keeps
  // its impulses for when it wakes.
  void step(double dt, std::span<const ContactManifold> contacts);
  // What the last step's contacts applied, in the order they were given (empty after a step
  // without contacts). Read out of the warm-start cache the first time it is asked for after
  // a step (about 10 ns per manifold), so a step whose caller never asks does not pay for it;
  // the reference stays valid until the next step.
  const std::vector<ContactReading>& contact_readings() const;

  SolverLayout solver_layout() const;
  // What the next step runs: the effects the awake content has, the stages and kernel
  // variants, awake bodies and sleeping islands. Built only when the content changed.
  const StepPlan& step_plan() const;

  // While on, every step records its first sub-step in solve_capture() (costs a copy of the
  // body state and an extra barrier per step; off by default).
  void set_solve_capture(bool on);
  const SolveCapture& solve_capture() const;

  // A joint's definition as created (rest_length already clamped into [min, max]).
  BallJointDef ball_joint(JointId id) const;
  DistanceJointDef distance_joint(JointId id) const;

  // While on, every step records where its time went (last_step_profile()).
  void set_profiling(bool on);
  const StepProfile& last_step_profile() const;
  // Hash of everything the world holds (bodies, joints, their impulses, settings, ids):
  // equal hashes mean equal worlds, bit for bit. For determinism checks and tests. The SIMD
  // width and thread count are left out: they never change a result.
  std::uint64_t state_hash() const;
  // Hash of every body's slot, pose and velocities only: cheap enough to take after every
  // step, which is what recordings do.
  std::uint64_t motion_hash() const;

  // Writes the world as it is now (a scene file's content) and from then on every call that
  // changes it and every step (dt, the contacts given to it, and the motion hash after it) to
  // a binary file at `path` (softstep/recording.hpp replays it). A world that has stepped can
  // be recorded (its scene keeps the joints' warm-start impulses, the contacts' warm-start
  // cache and the sleeping islands), unless it has destroyed bodies or joints, whose ids and
  // joint colouring a scene does not hold (the replay says so at its start). Throws
  // std::runtime_error when the file cannot be written; a recording already running is
  // stopped first.
  void start_recording(const std::string& path);
  // Ends the file with the world's state_hash and closes it. Nothing when not recording.
  void stop_recording();

  // A point given in world coordinates, expressed in the body's frame (for joint anchors).
  Eigen::Vector3d local_point(BodyId id, const Eigen::Vector3d& world_point) const;

  struct Impl;

 private:
  friend struct WorldInternals;  // the library's own files (world_impl.hpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace softstep
