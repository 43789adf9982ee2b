// What a step runs, built from the world's content (World::step_plan): only the stages and
// kernel variants the scene calls for. Rebuilt when the content changes, not every step.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "softstep/joints.hpp"
#include "softstep/world_settings.hpp"

namespace softstep {

// Stages of a step in run order. Gravity, Damping, Forces and SpinLimit run fused in one loop over
// the bodies (the velocity integration); a stage absent from the plan costs nothing: no
// loop, no barrier.
enum class PlanStage : std::uint8_t {
  PrepareBodies,       // body records from the world (once per step)
  PrepareJoints,       // anchors and softness coefficients (once per step)
  PrepareContacts,     // the step's contacts: effective masses, approach speeds (once per step)
  Gravity,             // per sub-step: some awake body feels gravity
  Damping,             // per sub-step: some awake body has linear or angular damping
  Forces,              // per sub-step: some awake body has a force or torque applied
  SpinLimit,           // per sub-step: the bounds on rotation per sub-step and on speed (always)
  WarmStart,           // per sub-step: last sub-step's impulses applied
  ClearImpulses,       // per sub-step: warm starting off
  Solve,               // per sub-step: soft, biased pass
  TreeSolve,           // per sub-step: the exact biased pass of tree islands (WorldSettings::solver)
  IntegratePositions,  // per sub-step
  Relax,               // per sub-step: only with rigid rows or limit rows (springs are not relaxed)
  TreeRelax,           // per sub-step: the exact unbiased pass of tree islands
  Restitution,         // after the sub-steps: only when some contact has restitution
  Store,               // poses and velocities back to the world (once per step)
};
// Store is last: the count follows the enum (two branches once each added stages to a literal).
inline constexpr int kPlanStageCount = static_cast<int>(PlanStage::Store) + 1;
const char* plan_stage_name(PlanStage stage);  // "prepare_bodies", "gravity", ...

// What the spring row of a kernel variant is: Any is the general kernel (per-lane switches).
enum class SpringRow : std::uint8_t { Any, Rigid, Soft, Free };
const char* spring_row_name(SpringRow row);  // "any", "rigid", "soft", "free"

// One kernel variant the step runs: the features it is compiled with and how much it runs.
// Ball and distance joints have compiled variants per spring kind and limit rows; the angular
// types run one kernel whose groups are packed by the parts they have, and skip the others.
struct PlanKernel {
  JointType type;
  SpringRow row;          // ball, distance: the spring row; Any for the general kernel
  bool lower_limit;       // distance joints: min-length row (the general kernel: per lane)
  bool upper_limit;       // distance joints: max-length row
  int rows_per_joint;     // constraint rows one joint solves per pass
  std::uint32_t batches;  // lane groups
  std::uint32_t joints;
  std::string parts;      // the parts its joints run: "point + hinge lock + limit + motor"
  bool compiled_variant;  // a variant compiled for exactly these parts (else a general kernel)
  // The bytes of its lane groups (padding lanes included) and, of those, the accumulated
  // impulses its passes write: what the memory-traffic model (step_traffic.hpp) counts.
  std::uint64_t lane_bytes = 0;
  std::uint64_t impulse_bytes = 0;
};

struct StepPlan {
  // Effects the awake content has.
  bool gravity = false;               // an awake dynamic body with gravity x gravity_scale != 0
  bool damping = false;               // an awake body with linear or angular damping
  bool forces = false;                // an awake body with apply_force / apply_torque pending
  bool springs = false;               // an awake joint with a soft spring
  bool limits = false;                // an awake joint with a limit row
  bool motors = false;                // an awake joint with a motor
  bool warm_start = false;            // settings().warm_start, with joints awake
  bool kinematic_bodies = false;      // an awake kinematic body
  bool unconstrained_bodies = false;  // an awake movable body with no joint
  bool specialized = true;            // false: WorldSettings::specialize is off (general kernels)
  std::vector<PlanStage> stages;      // in run order; Gravity..TreeRelax repeat every sub-step
  // WorldSettings::solver and what it did with the awake islands (solver/tree_solver.hpp).
  SolverMode solver = SolverMode::Iterative;
  std::size_t tree_islands = 0;   // solved exactly: their joints form a tree
  std::size_t tree_joints = 0;    // the joints of those islands
  // Of those, rooted at their centre and split in two parts (8 joints and more): an island of
  // 256 joints or more that is over a thread's share of tree_joints runs its parts on two
  // threads (a single long chain; solver/tree_solver.hpp).
  std::size_t tree_islands_split = 0;
  std::size_t loop_islands = 0;   // a loop through movable bodies: solved iteratively
  std::size_t other_islands = 0;  // a joint kind or spring the exact pass lacks: iterative
  // Every awake body is in an exactly solved island and no joint runs a Gauss-Seidel pass:
  // each island runs the step's sub-steps in turn (integration, exact solve, integration,
  // exact relax) while its state is in cache, rather than all islands once per stage; the
  // same bits either way. A step with contacts, the first step after new joints (its inertia
  // refresh) and a captured step run stage by stage.
  bool tree_islands_whole = false;
  std::vector<PlanKernel> kernels;    // ordered by type, then variant
  std::size_t awake_bodies = 0;       // movable bodies integrated each sub-step
  std::size_t sleeping_islands = 0;
  std::uint64_t rows_per_pass = 0;  // constraint rows one solve pass runs (joints)
  // The last step's contacts (they come with each step, World::step(dt, contacts)): the
  // manifolds in lanes, their points, the colours they took and how many found none (solved in
  // order on one thread), and the rows they brought. Their stages join the plan only while
  // there are contacts; friction, rolling and restitution only while some contact has them.
  std::size_t contact_manifolds = 0;
  std::size_t contact_points = 0;
  std::size_t contact_colors = 0;
  std::size_t contact_overflow = 0;
  bool contact_friction = false;
  bool contact_rolling = false;
  bool contact_restitution = false;
  std::uint64_t builds = 0;         // how many times this world has built its plan

  bool runs(PlanStage stage) const;  // stage is in `stages`
};

}  // namespace softstep
