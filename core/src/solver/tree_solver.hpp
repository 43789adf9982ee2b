// WorldSettings::solver = DirectForTrees / Auto: which islands are solved exactly
// (tree_system.hpp) and the passes that do it, after the Gauss-Seidel solve and relax of each
// sub-step. In a mixed world the Gauss-Seidel passes still run over these joints first; when
// every awake joint is in such an island the plan leaves them out (step_plan.cpp). Either way
// the exact pass moves each island's velocities and impulses from wherever they are to the
// exact solution of the sub-step's system with rigid rows: Gamma = 0, bias = bias_rate C
// bounded per row by max_correction_speed while solving, no bias while relaxing. The relax
// pass then also projects the positions: with the same factor it solves J dx = -C and moves
// the bodies by dx (no velocity change). It removes all the drift the step's own motion made,
// and of a violation already there at the step's start (joints created apart, a body the user
// moved) at most max_correction_speed * h per sub-step. Without it the exact velocities
// still drift where links spin fast: the 1,000-link whip's tip turns ~1 rad per sub-step as it
// cracks (254 rad/s, 261 m/s), and the first-order rotation update opened a joint 0.19 m; with
// the whole of C bounded, 2.1 cm. Where nothing but the velocity integration changes the
// velocities between a relax pass and the next sub-step's solve pass (an island of an
// exact-only world that no contact touches and no damping slows), the relax pass also solves
// what that solve pass would (Pass::fold_next), and the solve pass runs only at a step's first
// sub-step, where it solves with the last step's last relax factor (Pass::reuse_relax_factor):
// a step factors each island once per sub-step.
//
// Handles rigid ball joints and rigid distance joints. An island (movable bodies linked by
// joints) with any other joint (soft, free, limited, revolute, prismatic, weld, ...), with
// a loop through its movable bodies, or with more than one joint to a static or kinematic
// body (a loop through the ground, tree_system.cpp) stays iterative; StepPlan counts them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "slot_vectors.hpp"
#include "softstep/simd/step_context.hpp"
#include "softstep/world_settings.hpp"
#include "solver/joint_batches.hpp"
#include "solver/tree_system.hpp"

namespace softstep {
struct ContactManifold;
struct SolverBodies;
class LaneSolver;
}  // namespace softstep

namespace softstep::solver {

struct TreeCounts {
  std::size_t tree_islands = 0;  // solved exactly
  std::size_t tree_joints = 0;
  std::size_t tree_bodies = 0;
  // A loop through movable bodies, or through the ground (more than one joint to a static or
  // kinematic body): iterative.
  std::size_t loop_islands = 0;
  std::size_t other_islands = 0;  // a joint the exact pass does not handle: iterative
  // Of the tree islands, those rooted at their centre in two parts (TreeSystem::split): one
  // that is most of a step's exact work runs its two parts on two threads.
  std::size_t split_islands = 0;
};

class TreeSolver {
 public:
  // Finds the islands to solve exactly among the joints in the lanes (awake).
  void build(SolverMode mode, const JointSlots& joints, const BodySlots& bodies,
             const LaneSolver& lanes);
  bool empty() const { return islands_.empty(); }
  const TreeCounts& counts() const { return counts_; }
  // Before a step's stages: which islands the step's contacts touch (a body of theirs in a
  // manifold). Their relax passes do not fold the next sub-step's solve pass in (the contact
  // passes change their velocities between); the other islands fold as in a world without
  // contacts (Island::contacted). The manifolds have been checked (bodies that exist).
  void mark_contacts(std::span<const ContactManifold> manifolds);
  // Which exact pass this is.
  struct Pass {
    bool with_bias = true;  // the solve pass (with the bias), or the relax pass (without)
    // The step's first pass: the joints' step-start anchors are turned into the world frame
    // once here (the bodies' step-start poses do not change until the step ends).
    bool step_start = false;
    // A solve pass that solves with the island's last relax pass's factor (its Jacobians and
    // masses) instead of a new one. Where the caller says:
    // - at a sub-step whose masses have not changed since the last relax pass (the bodies
    //   moved only by its projection): against the factor's own Jacobians (C is today's), as
    //   a relax pass that folds this solve pass in solves it (fold_next);
    // - at a step's first sub-step, after the last step's last relax pass: the masses
    //   re-read (the geometric inertia is new) and taken by the velocity changes, and against
    //   today's residual, J v from the rows at the bodies' poses now: one step of an iteration
    //   on today's system preconditioned by a nearby one, leaving of the residual the order of
    //   the difference; the relax pass after it solves the sub-step's velocities with a factor
    //   of its own. One factor a step fewer where the relax passes fold the other solve
    //   passes (the 1,000-link whip's exact step 0.47 -> 0.44 ms, Zen 5).
    // Today's J v at a step's start: the relax pass solved J v = 0 with its own Jacobians,
    // before its projection moved the bodies, so against them this solve finds nothing to do
    // but the bias, and it is then the step's only velocity solve that meets the Jacobians
    // after a projection. Without it the velocities drift from the positions step after step:
    // the 10 links + 1e6 kg ball hard case, with the bias at its least, opened to 159 m
    // (3.9e-6 of its length with today's J v; HardCaseDirect in hard_cases_test.cpp); at the
    // default bias 9.4e-6 against 1.3e-6 with today's J v and 1.1e-7 with a factor of its own.
    bool reuse_relax_factor = false;
    // Adds the pass's impulse changes to the joints' lane impulses (whole_substeps: the last
    // sub-step's passes only).
    bool add_impulses = true;
    // A relax pass that also solves, with its factor, what the next sub-step's velocity
    // integration will add (gravity and applied forces: `gravity`; applied torques: `torque`)
    // and adds that velocity change's constraint response now: the next sub-step's solve pass
    // then has nothing left to do but hand over its impulses. For a sub-step whose velocities
    // only the integration changes before its solve pass (no Gauss-Seidel pass over these
    // joints, no inertia refresh: step.cpp), and adds to them only: an island that a contact
    // touches does not fold, whatever the pass says (Island::contacted), nor one with a damped
    // body (Island::damped; damping scales the velocities this pass leaves, linear and angular
    // by their own factors, body by body, and J of what it takes off is not known until this
    // pass has solved; 20 links with linear or angular damping of 1/s ended 8.1e-5 / 6.6e-5 m
    // from the one solved sub-step by sub-step, 30-50x what the fold leaves without damping;
    // the damping stage scales an undamped body's velocities by exactly 1). The velocities it
    // leaves are not those of a sub-step's end, so never for a step's last sub-step.
    bool fold_next = false;
    bool gravity = false, torque = false;
    // With fold_next: whether the folded solve pass's impulses are read, which a sub-step's
    // lane impulses are only at a step's last sub-step (every earlier sub-step clears them,
    // and an island stepped whole hands over the last sub-step's passes' only). Where they
    // are not, the folded velocity change is solved with this pass's own as one right side
    // (J v + J of that change) instead of as a column of its own: two columns where there were
    // three, at every sub-step but the last two.
    bool fold_apart = true;
    // A relax pass that measures the joints after its projection and runs Newton steps where
    // one is still open by more than a tolerance (tree_solver.cpp). Needed at a step's last
    // sub-step only: at the others the next sub-step's projection takes out what is left with
    // the drift of its own motion (and the check's pass over the joints and, shared, its two
    // barriers are saved).
    bool check = true;
    // The relax pass of sub-step `sub` of `substeps`, for both ways of stepping (pass and
    // whole_substeps): `may_fold` when nothing but the velocity integration's additions change
    // the islands' velocities before the next sub-step's solve pass (fold_next; step.cpp).
    static Pass relax(int sub, int substeps, bool may_fold, bool gravity, bool torque) {
      const bool last = sub + 1 == substeps;
      return {.with_bias = false,
              .fold_next = may_fold && !last,
              .gravity = gravity,
              .torque = torque,
              .fold_apart = sub + 2 == substeps,
              .check = last};
    }
  };
  // One exact pass over this thread's islands. Writes the bodies' velocities and adds to the
  // joints' lane impulses; the relax pass also moves the bodies' positions. An island that is
  // more than a thread's share of the exact joints (a single long chain) is shared: with two
  // threads or more, threads 0 and 1 each run one of its parts (tree_system.hpp) and meet at
  // team barriers; every thread of the team must call.
  void pass(const JointSlots& joints, const BodySlots& bodies, SolverBodies& solver_bodies,
            LaneSolver& lanes, const simd::SubstepContext& ctx, Pass which, const Share& share);
  // The step's sub-steps, island after island (StepPlan::tree_islands_whole): each of this
  // thread's islands runs all of them in turn, its bodies integrated on their own, while its
  // state is in cache, instead of every island once per stage. The same operations on the
  // same data in the same order per island as the stages run them: the same bits. Only for a
  // step whose every awake body is in such an island, no joint runs a Gauss-Seidel pass, no
  // contact, no inertia refresh between sub-steps and no capture (step.cpp); the lanes'
  // impulses cleared before.
  struct Whole {
    int substeps;
    bool gravity, damping, torque;  // the integration's terms, as the stages take them
    bool relax;                     // the relax pass runs (relax_iterations > 0)
  };
  void whole_substeps(const JointSlots& joints, const BodySlots& bodies,
                      SolverBodies& solver_bodies, LaneSolver& lanes,
                      const simd::SubstepContext& ctx, const Whole& whole, const Share& share);

 private:
  struct Anchors {
    Eigen::Vector3d r_a, r_b, separation;
  };
  // An island's bodies and joints (island-local indices) in one of its two parts
  // (TreeSystem::body_part, joint_part), with the bodies' solver records: in runs of
  // kBodyBlock consecutive ones (the first of each) that the body kernels integrate a lane per
  // record, and the rest one by one (a chain's links one by one were 7 % of the 1,000-link
  // whip's exact step, Zen 5).
  struct Part {
    std::vector<std::uint32_t> bodies, joints;
    std::vector<std::int32_t> record_runs, single_records;
  };
  struct Island {
    std::vector<std::uint32_t> bodies;             // movable body slots (island-local order)
    std::vector<std::uint32_t> joints;             // joint slots
    Part parts[2];
    std::vector<std::int32_t> solver_a, solver_b;  // per joint its bodies' solver records
    std::vector<TreeJoint> rows;                   // per joint, refilled each pass
    // Per joint, a distance joint's rest length (0 for the other kinds; the kind is in its
    // row, TreeJoint::ball). Kept with the island (built again after any set_joint: it marks
    // the plan stale), so that only a step's first pass reads the joints' slots, a cache line
    // each of a struct sized for every kind (at most 2 % of the whip's exact step, Zen 5).
    std::vector<double> rest_length;
    std::vector<InverseMass> inverse_mass;
    std::vector<Vec6> dv;
    std::vector<Eigen::Vector3d> dp;
    // C per joint (padding rows 0) that the relax pass's projection removes, refilled by it
    std::vector<Eigen::Vector3d> error;
    // Per joint, how much of its violation (m, violation_size) was there at the step's start
    // and is still to close: each projection removes at most max_correction_speed * h of it.
    std::vector<double> held_back;
    // Per joint, the part of C the last projection left on purpose (of the held-back part).
    std::vector<Eigen::Vector3d> kept;
    // Per joint, set at the step's start: both anchors turned by their body's step-start
    // orientation, and the step-start offset from body a to body b.
    std::vector<Eigen::Vector3d> anchor_a, anchor_b, offset;
    // Per joint, its anchors turned to where the bodies are and their separation, as the
    // relax pass's check measured them after its projection (its Newton step's rows). The
    // check runs at a step's last sub-step, after which the next pass turns them again.
    std::vector<Anchors> anchors;
    std::vector<Vec6x2> dv_pair;  // the relax pass's: velocity change, position change
    std::vector<Vec3x2> dp_pair;  // its impulse change, position multiplier
    // A folding relax pass's (Pass::fold_next): the same and the next sub-step's velocity
    // change and impulse; per joint the right side of that third column, J of that change.
    std::vector<Eigen::Matrix<double, 6, 3>> dv_triple;
    std::vector<Eigen::Matrix<double, 3, 3>> dp_triple;
    std::vector<Eigen::Vector3d> next_change;
    // The last relax pass folded the next sub-step's solve pass in (Pass::fold_next).
    bool folded = false;
    // It did so without a column of its own for it (Pass::fold_apart false): no impulses to
    // hand over.
    bool folded_together = false;
    // A body of the island is damped (linear or angular, fixed at its creation): its relax
    // passes do not fold the next sub-step's solve pass in (Pass::fold_next). Per island, so
    // that one damped body elsewhere does not cost every island its fold.
    bool damped = false;
    // A body of the island is in one of this step's contact manifolds (mark_contacts): its
    // relax passes do not fold either, as the contact passes change its velocities between a
    // relax pass and the next sub-step's solve pass. Per island, so that a contact elsewhere
    // does not cost every island its fold (until 2026-11-29 any contact did).
    bool contacted = false;
    // Per part, the largest joint gap the relax pass's last check left (its Newton steps).
    double worst[2] = {0.0, 0.0};
    TreeSystem system;
    bool relax_factored = false;  // the system holds the last pass's factor, a relax pass's
  };
  // Who works on one island: one thread alone (both parts and the root part, no barrier), or
  // one of a team sharing it (thread 0 part 0 and the root part, thread 1 part 1, any other
  // only the barriers).
  struct Crew {
    int first_part = 0, end_part = 2;  // this thread's parts: [first_part, end_part)
    bool lead = true;                  // runs the root part
    const Share* team = nullptr;       // when shared: a team barrier between phases
    void sync() const;
  };
  static Crew alone() { return {}; }
  static Crew member_of(const Share& share);
  // Whether a team of `threads` shares this island (a single long chain): an island of
  // kShareMinJoints or more that is split and more than a thread's share of the exact joints.
  bool shared(const Island& island, int threads) const;
  void solve_island(Island& island, const JointSlots& joints, const BodySlots& bodies,
                    SolverBodies& solver_bodies, LaneSolver& lanes, const simd::SubstepContext& ctx,
                    Pass which, const Crew& crew);
  void whole_island(Island& island, const JointSlots& joints, const BodySlots& bodies,
                    SolverBodies& solver_bodies, LaneSolver& lanes, const simd::SubstepContext& ctx,
                    const Whole& whole, const Crew& crew);
  std::vector<Island> islands_;
  std::vector<std::int32_t> island_of_slot_;  // per body slot its island's index, or -1
  TreeCounts counts_;
};

}  // namespace softstep::solver
