// The world's storage. Cold records (what a body or joint *is*) live in slots addressed by
// id; the solver's hot state (body records, joint lanes) is rebuilt from them.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "contacts/contact_solver.hpp"
#include "joints/joint_registry.hpp"
#include "slot_vectors.hpp"
#include "softstep/graph_coloring/graph_coloring.hpp"
#include "softstep/simd/body_integration.hpp"
#include "softstep/simd/step_context.hpp"
#include "softstep/step_plan.hpp"
#include "softstep/world.hpp"
#include "solver/joint_batches.hpp"
#include "solver/tree_solver.hpp"
#include "thread_policy.hpp"

namespace softstep {

namespace recording {
class Recorder;
}

struct BodySlot {
  std::uint32_t generation = 0;
  bool alive = false;
  BodyType type = BodyType::Dynamic;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Quaternion orientation = Quaternion::Identity();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Zero();  // body frame; 0 unless dynamic
  bool diagonal_inertia = true;  // body frame tensor is diagonal: I + c 1 inverts entrywise
  double gravity_scale = 1.0;
  double linear_damping = 0.0;
  double angular_damping = 0.0;
  // Applied with apply_force / apply_torque for the next step, world frame, about the centre
  // of mass: N and N m. Cleared after that step.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  std::vector<std::uint32_t> joints;  // slots of the joints attached to this body
  bool never_sleep = false;
  std::uint64_t user_data = 0;  // the caller's; never read, validated or hashed
  bool asleep = false;
  double sleep_time = 0.0;  // s the body has stayed below the sleep speeds
  // How far the last step moved the body: |displacement|^2 (m^2) and |rotation quaternion
  // xyz|^2 (sin^2 of half the angle). A body that a joint's bounded correction is pulling
  // moves while the relax pass leaves its velocity near zero: the sleep test reads both.
  float step_moved2 = 0.0f;
  float step_turned2 = 0.0f;
  std::uint32_t island = 0;  // while asleep: index into World::Impl::islands
};

struct JointSlot {
  std::uint32_t generation = 0;
  bool alive = false;
  JointType type = JointType::Ball;
  std::uint32_t body_a = 0;  // body slots
  std::uint32_t body_b = 0;
  Eigen::Vector3d local_anchor_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d local_anchor_b = Eigen::Vector3d::Zero();
  JointDefs def;  // the definition as validated: the type's own settings (joints/*_joint.cpp)
  std::uint64_t user_data = 0;  // the caller's; never read, validated or hashed
  // Accumulated impulses kept here while the joint is not in the solver's lanes (between a
  // topology change and the next pack), in the order of its kind's read_impulses.
  std::array<float, kMaxJointImpulses> impulse{};
  // Revolute: the hinge angle at the last step's start, rad, unwrapped (revolute_joint.cpp).
  double angle = 0.0;
};

// The solver's body index: 0 is the static dummy; a movable body in slot s is s + 1.
inline std::int32_t solver_index(const BodySlot& body, std::uint32_t slot) {
  return body.type == BodyType::Static ? simd::kDummyBody : static_cast<std::int32_t>(slot) + 1;
}

struct SolverBodies {
  PagedVector<simd::VelocityRecord> velocity;
  PagedVector<simd::DeltaRecord> delta;
  PagedVector<simd::MassRecord> mass;
  PagedVector<simd::ForceRecord> force;
  // Slots of the awake dynamic and kinematic bodies, in slot order.
  std::vector<std::uint32_t> movable;
  // First records of the blocks of 8 that hold an awake movable body: integration runs over
  // them only (the other records in such a block are static, free or asleep: zero velocity,
  // no force, which integrate to themselves exactly).
  std::vector<std::int32_t> blocks;
  simd::BodyArrays arrays() { return {velocity.data(), delta.data(), mass.data()}; }
};

// A kernel variant in the lanes: which, and how much of it (see solver/joint_batches.hpp).
struct KernelUse {
  JointType type;
  std::uint8_t variant;     // index into the kind's variants
  std::uint32_t signature;  // the parts its joints run (kinds that pack by signature)
  PlanKernel plan{};        // as the plan shows it, without the counts
  std::uint32_t batches = 0;
  std::uint32_t joints = 0;
};

// The joints of one lane width in coloured batches; see lane_solver.cpp.
class LaneSolver {
 public:
  enum class Pass { Solve, Relax };
  virtual ~LaneSolver() = default;
  virtual int lanes() const = 0;
  // Lays out the awake joints from the colouring; impulses come from the slots. specialize:
  // each joint runs the kernel variant of its signature, else the general kernel.
  virtual void pack(const graph_coloring::GraphColoring& coloring, const JointSlots& joints,
                    const BodySlots& bodies, bool specialize) = 0;
  // Copies the lanes' impulses back into the slots (before a re-pack).
  virtual void save_impulses(JointSlots& joints) const = 0;
  virtual bool in_lanes(std::uint32_t joint_slot) const = 0;
  // The joint's accumulated impulses (its kind's kImpulses floats), when in_lanes.
  virtual std::array<float, kMaxJointImpulses> impulses(std::uint32_t joint_slot) const = 0;
  // Adds to the joint's accumulated impulses (the exact tree pass, solver/tree_solver.hpp); only
  // for kinds with an add_impulses (ball, distance), when in_lanes.
  virtual void add_impulses(std::uint32_t joint_slot, const float* delta) = 0;
  // After set_joint: rewrites the joint's lane from its slot when it runs the same kernel and
  // signature as before, keeping its impulses; false when it needs a re-pack instead.
  virtual bool refresh(std::uint32_t joint_slot, const JointSlots& joints, bool specialize) = 0;
  // destroy_joint: turns the joint's lane into a padding lane (both bodies the static dummy,
  // which no kernel writes), so the colouring and every other lane stay as they are; false
  // when the joint is not in the lanes.
  virtual bool vacate(std::uint32_t joint_slot) = 0;
  virtual const std::vector<KernelUse>& uses() const = 0;
  virtual bool needs(Pass pass) const = 0;  // some variant in the lanes runs this pass
  // extra[body] += factor * tension * |local anchor| for both dynamic bodies of every joint
  // (tension: the magnitude of its linear impulse, its kind's tension(); a body is dynamic when
  // dynamic[body] != 0, World::Impl::dynamic_body; a slider's A takes the lever from its centre
  // to B's anchor, read from `bodies`); this thread's share, ending at a team barrier.
  virtual void accumulate_geometric_inertia(const JointSlots& joints, const BodySlots& bodies,
                                            const std::vector<std::uint8_t>& dynamic, double factor,
                                            std::vector<double>& extra,
                                            const solver::Share& share) const = 0;
  // The stages of a step. Every thread of the step calls each with its Share; the stages
  // that run colour by colour meet at a barrier after each colour and after the overflow set,
  // the others touch only the thread's own groups or bodies (callers put the barriers).
  // Writes the step-start anchors and the rows' softness coefficients.
  virtual void prepare(JointSlots& joints, const BodySlots& bodies, const simd::BodyArrays& arrays,
                       const simd::SubstepContext& ctx, const solver::Share& share) = 0;
  virtual void warm_start(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                          const solver::Share& share) = 0;
  virtual void clear_impulses(const solver::Share& share) = 0;
  virtual void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                     const solver::Share& share) = 0;
  virtual void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                     const solver::Share& share) = 0;
  virtual void integrate_velocities(SolverBodies& bodies, const simd::SubstepContext& ctx,
                                    bool gravity, bool damping, bool torque,
                                    const solver::Share& share) = 0;
  virtual void integrate_positions(SolverBodies& bodies, const simd::SubstepContext& ctx,
                                   const solver::Share& share) = 0;
  // The same for the given records only (one thread's, no Share): a tree island's bodies,
  // as runs of kBodyBlock consecutive records (the first of each; integrated a lane per record,
  // as the blocks above) and single records. Every record integrates alone: the same bits
  // either way.
  struct RecordRuns {
    std::span<const std::int32_t> runs, singles;
  };
  virtual void integrate_velocities_of(SolverBodies& bodies, RecordRuns records,
                                       const simd::SubstepContext& ctx, bool gravity, bool damping,
                                       bool torque) = 0;
  virtual void integrate_positions_of(SolverBodies& bodies, RecordRuns records,
                                      const simd::SubstepContext& ctx) = 0;
};

// The slot of a live body or joint; rejects unknown and destroyed ids naming `field` (world.cpp).
std::uint32_t body_slot(const World::Impl& w, std::string_view call, std::string_view field,
                        BodyId id);
std::uint32_t joint_slot(const World::Impl& w, std::string_view call, JointId id);

// Set by core/CMakeLists.txt for each width in SOFTSTEP_WIDTHS: a width left out has no
// kernels, and the code that picks a width compiles its case out.
#ifndef SOFTSTEP_HAS_SSE
#define SOFTSTEP_HAS_SSE 0
#endif
#ifndef SOFTSTEP_HAS_AVX2
#define SOFTSTEP_HAS_AVX2 0
#endif
#ifndef SOFTSTEP_HAS_AVX512
#define SOFTSTEP_HAS_AVX512 0
#endif

std::unique_ptr<LaneSolver> make_lane_solver(SimdWidth width);
SimdWidth best_simd_width();
// Whether this build compiled the width's kernels (SOFTSTEP_WIDTHS).
bool simd_width_built(SimdWidth width);
// Built, and this CPU runs it.
bool simd_width_supported(SimdWidth width);
// The instruction sets a width needs, as a CPU's documentation names them ("AVX2 and FMA").
std::string simd_width_requirement(SimdWidth width);

struct World::Impl {
  WorldSettings settings;
  BodySlots bodies;
  std::vector<std::uint32_t> free_bodies;  // slots to reuse, last freed first
  JointSlots joints;
  std::vector<std::uint32_t> free_joints;
  std::size_t body_count = 0;
  std::size_t joint_count = 0;

  graph_coloring::GraphColoring coloring;
  SimdWidth width = SimdWidth::Scalar;  // resolved, never Best
  std::unique_ptr<LaneSolver> lane_solver;
  // The step's contacts (contacts/contact_solver.hpp), the impulses the last step's left for
  // warm starting, and what they applied.
  std::unique_ptr<ContactSolver> contact_solver;
  ContactCache contact_cache;
  ContactCache contact_cache_next;  // filled by a step, then swapped in
  // What the last step's contacts applied, read out of contact_cache when first asked for
  // (World::contact_readings): a step whose caller never asks does not write them (0.4 ms of
  // the 5,050-box pyramid's 6.5 ms on one thread). Whatever changes contact_cache between
  // steps settles them first, so they stay the step's.
  mutable std::vector<ContactReading> contact_readings;
  mutable bool contact_readings_pending = false;
  void settle_contact_readings() const {
    if (!contact_readings_pending) return;
    read_out(contact_cache, contact_readings);
    contact_readings_pending = false;
  }
  bool joints_packed = false;  // false after any joint change: re-pack before the next step
  bool bodies_listed = false;  // false after any body change: rebuild the movable list
  // Counts content_changed(): the contact solver keeps its layout only while it stays.
  std::uint64_t bodies_version = 0;
  SolverBodies solver_bodies;
  std::vector<double> extra_inertia;  // per body slot, from geometric_inertia (awake entries)
  // Per body slot, 1 for a dynamic body, listed with the bodies (list_bodies: a body's type is
  // fixed for its life, and creating or destroying one lists them again). The geometric
  // inertia's sums test both bodies of every joint: reading the type from the 424-byte body
  // slots made those sums 20-35 % slower (the 100 x 100 grid, alternated by step in one
  // process: 213-242 against 146-189 us per step).
  std::vector<std::uint8_t> dynamic_body;
  bool extra_inertia_on = false;      // this step adds extra_inertia
  double last_substep = 0.0;          // s, of the last step (for joint forces)
  // A joint was created since the last step: it has no force for the geometric inertia yet,
  // so the next step recomputes that inertia after its first sub-step (see step.cpp).
  bool joints_without_history = false;
  // Chooses one thread or all for each step from how fast recent steps ran with each.
  // Results do not depend on the count, so it may change at any step.
  ThreadPolicy thread_policy;  // one thread or all, for steps large enough to share
  TaskCallbacks tasks;  // the host's job system; enqueue == nullptr: OpenMP
  bool profiling = false;
  StepProfile profile;  // of the last step, while profiling
  bool capturing = false;
  SolveCapture capture;  // of the last step, while capturing (solve_capture.cpp)
  StepPlan plan;
  solver::TreeSolver trees;  // the islands WorldSettings::solver solves exactly (build_plan)
  bool plan_built = false;  // false after any change of content or settings
  std::unique_ptr<recording::Recorder> recorder;  // while recording (recording/recorder.cpp)

  // Bodies given a force or torque for the next step (may repeat a slot); cleared by the step.
  std::vector<std::uint32_t> forced_bodies;
  // Sets StepPlan::forces and its stage in a built plan without rebuilding it: forces come
  // and go every step in a game, the rest of the content does not.
  void plan_forces(bool on);
  void clear_forces();  // after a step
  // Sets the plan's contact fields and stages for this step's contacts, without rebuilding it,
  // and keeps the layout for plans rebuilt before the next step.
  void plan_contacts(const ContactLayout& layout);
  std::vector<PlanStage> contact_stages;  // the stages plan_contacts added to the plan
  // The last planned step's contact layout. Not the solver's: a step whose checks fail may
  // have laid its contacts out beside them (step.cpp), and must leave the plan as it was.
  ContactLayout planned_contacts;

  // Sleeping islands: the body slots of each, in slot order; emptied when woken.
  std::vector<std::vector<std::uint32_t>> islands;
  std::vector<std::uint32_t> free_islands;  // last freed first
  std::size_t sleeping_islands = 0;
  std::vector<std::uint32_t> island_root;   // per body slot, scratch of update_sleep
  std::vector<double> island_rest;          // per body slot, scratch of update_sleep
  std::vector<std::uint32_t> island_index;  // per body slot, scratch of update_sleep

  // A joint's accumulated impulses, from its lanes while packed, else from its slot.
  std::array<float, kMaxJointImpulses> joint_impulses(std::uint32_t slot) const {
    return joints_packed && lane_solver->in_lanes(slot) ? lane_solver->impulses(slot)
                                                        : joints[slot].impulse;
  }
  void unpack_joints();    // save impulses to slots and mark for re-pack
  void content_changed();  // bodies or joints to re-list and re-pack, plan to rebuild
  void build_plan();       // packs, lists and plans if anything changed
  // The user touched this body: its island wakes, and it starts its rest time again.
  void touch(std::uint32_t body_slot);
  void wake_island(std::uint32_t island);
  void wake_all();
  // A step's test of whether a body rested (sleep.cpp): the sleep speeds as this step's bounds.
  struct RestTest {
    bool on = false;  // settings.sleeping
    double dt = 0.0;
    float moved2 = 0.0f, turned2 = 0.0f;  // squared bounds of what the step moved and turned it
  };
  RestTest rest_test(double dt) const;
  // Adds dt to the body's rest time if it rested this step, else restarts it; true once it has
  // rested time_to_sleep. finalize_bodies runs it on each thread's share of the awake bodies,
  // while their slots are in the cache (a pass of its own over 100,000 slots was 9 % of the
  // main job's step, on one thread whatever the thread count).
  bool update_rest_time(BodySlot& b, const RestTest& test) const;
  // After a step: islands whose bodies all rested time_to_sleep fall asleep. `some_ready`:
  // update_rest_time said true for some body this step.
  void update_sleep(bool some_ready);
  void sleep_island(const std::vector<std::uint32_t>& members);
  // Per body slot, the inertia (kg m^2, added on the diagonal) that keeps the alignment
  // mode resolvable at sub-step h: h^2 sum over its joints of |force| |anchor offset|, the
  // forces being the lanes' impulses over `impulse_substep` (s; 0: none known, no pass).
  // Whether impulses of that sub-step give geometric inertia (the setting, awake joints).
  bool geometric_inertia_applies(double impulse_substep) const;
  // Before the team: whether the step starts with it (extra_inertia_on) and room for it,
  // also when the second sub-step will `refresh` it.
  void plan_geometric_inertia(double impulse_substep, bool refresh);
  // In the team, each thread its share; ends at a barrier.
  void geometric_inertia(float h, double impulse_substep, const solver::Share& share);
  // Rewrites this thread's share of the dynamic bodies' mass records from extra_inertia.
  void refresh_inertia(const solver::Share& share);
  void list_bodies();  // (re)sizes the records and the movable list after body changes
  void prepare_bodies(float h, const solver::Share& share);
  // Stores this thread's share of the awake bodies' poses and velocities and their rest
  // times; returns whether any of them is ready to sleep.
  bool finalize_bodies(const solver::Share& share, const RestTest& rest);
  // The three moments of a step the solve capture records (serial: thread 0 only).
  void capture_step_start(float h, double rigid_hertz);
  void capture_before_solve();  // velocities after gravity and damping, the solver's masses
  void capture_solved();        // velocities and impulses after the first sub-step's solve
};

// The library's own way into a World, for what the API does not set (scene files restoring
// warm-start impulses, for one).
struct WorldInternals {
  static World::Impl& of(World& world) { return *world.impl_; }
  static const World::Impl& of(const World& world) { return *world.impl_; }
};

}  // namespace softstep
