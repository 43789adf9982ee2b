// The step plan: which effects the awake content has, and from them the stages and kernel
// variants a step runs. Built when the content or the settings changed, never per step.
#include <algorithm>

#include "solver/joint_batches.hpp"
#include "world_impl.hpp"

namespace softstep {

void World::Impl::build_plan() {
  if (!joints_packed || !bodies_listed) thread_policy.restart();  // new content: measure afresh
  if (!joints_packed) {
    lane_solver->pack(coloring, joints, bodies, settings.specialize);
    joints_packed = true;
    plan_built = false;
  }
  if (!bodies_listed) {
    list_bodies();
    plan_built = false;
  }
  if (plan_built) return;

  StepPlan p;
  p.builds = plan.builds + 1;
  p.specialized = settings.specialize;
  p.awake_bodies = solver_bodies.movable.size();
  p.sleeping_islands = sleeping_islands;
  for (std::uint32_t s : solver_bodies.movable) {
    const BodySlot& b = bodies[s];
    if (b.type == BodyType::Kinematic) {
      p.kinematic_bodies = true;
    } else {
      p.gravity |= b.gravity_scale != 0.0 && !settings.gravity.isZero(0.0);
      p.damping |= b.linear_damping > 0.0 || b.angular_damping > 0.0;
      p.forces |= !b.force.isZero(0.0) || !b.torque.isZero(0.0);
    }
    p.unconstrained_bodies |= b.joints.empty();
  }
  for (const KernelUse& u : lane_solver->uses()) {
    PlanKernel k = u.plan;
    k.batches = u.batches;
    k.joints = u.joints;
    p.rows_per_pass += std::uint64_t(k.rows_per_joint) * k.joints;
    p.kernels.push_back(std::move(k));
  }
  // The general kernel's joints say per lane; look at them to tell the effects.
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    const JointSlot& slot = joints[j];
    if (!slot.alive || !lane_solver->in_lanes(j)) continue;
    JointKinds::with(slot.type, [&]<class Kind>() {
      const JointEffects e = Kind::effects(slot);
      p.springs |= e.springs;
      p.limits |= e.limits;
      p.motors |= e.motors;
    });
  }
  const bool joints_awake = !p.kernels.empty();
  p.warm_start = joints_awake && settings.warm_start;

  // Specialized, a stage runs only for an effect present; general, every stage runs (a
  // gravity of 0, a damping of 1, a spring that does nothing).
  const bool all = !settings.specialize;
  const bool bodies_awake = p.awake_bodies > 0;
  const bool solve = joints_awake && (all || lane_solver->needs(LaneSolver::Pass::Solve));
  const bool relax = joints_awake && settings.relax_iterations > 0 &&
                     (all || lane_solver->needs(LaneSolver::Pass::Relax));
  trees.build(settings.solver, joints, bodies, *lane_solver);
  p.solver = settings.solver;
  p.tree_islands = trees.counts().tree_islands;
  p.tree_joints = trees.counts().tree_joints;
  p.tree_islands_split = trees.counts().split_islands;
  p.loop_islands = trees.counts().loop_islands;
  p.other_islands = trees.counts().other_islands;
  const bool exact = joints_awake && !trees.empty();
  // Every awake joint in an exactly solved island: no Gauss-Seidel pass for them. They would
  // only warm-start the exact pass, whose solution does not depend on where they leave the
  // velocities (it projects onto J v = -bias from wherever they are), and its impulses
  // cleared at each sub-step's start come out the same as the warm-started ones (the warm
  // start's impulse is taken back by the exact pass). They were a third of the whip's step
  // at 1,000 links. Nor do they need the lanes' preparation (world anchors, effective masses:
  // the exact pass turns its own anchors, and a ball or distance joint writes nothing else at
  // the step's start); the lanes still carry their impulses (ClearImpulses, the exact pass's
  // add_impulses, the readings and the geometric inertia). Contacts add their stages to the
  // plan (plan_contacts) without running the joints' passes (step.cpp, joints_run). Mixed
  // worlds keep the passes and the preparation (the other joints need them).
  std::size_t lane_joints = 0;
  for (const PlanKernel& k : p.kernels) lane_joints += k.joints;
  const bool exact_only = exact && trees.counts().tree_joints == lane_joints;
  // Kinematic bodies and bodies without joints are awake but in no island: stage by stage.
  p.tree_islands_whole = exact_only && trees.counts().tree_bodies == p.awake_bodies;
  const auto add = [&](bool on, PlanStage stage) {
    if (on) p.stages.push_back(stage);
  };
  add(bodies_awake, PlanStage::PrepareBodies);
  add(joints_awake && !exact_only, PlanStage::PrepareJoints);
  add(bodies_awake && (all || p.gravity), PlanStage::Gravity);
  add(bodies_awake && (all || p.damping), PlanStage::Damping);
  add(bodies_awake && (all || p.forces), PlanStage::Forces);
  add(bodies_awake, PlanStage::SpinLimit);
  add(solve && settings.warm_start && !exact_only, PlanStage::WarmStart);
  add(joints_awake && (!settings.warm_start || exact_only), PlanStage::ClearImpulses);
  add(solve && !exact_only, PlanStage::Solve);
  add(exact, PlanStage::TreeSolve);
  add(bodies_awake, PlanStage::IntegratePositions);
  add(relax && !exact_only, PlanStage::Relax);
  add(exact && settings.relax_iterations > 0, PlanStage::TreeRelax);
  add(bodies_awake, PlanStage::Store);
  plan = std::move(p);
  contact_stages.clear();
  plan_built = true;
  // Until the next step hands its own contacts, the plan shows the last step's, as a plan that
  // is not rebuilt does: a profile that reads the plan after a step whose end put bodies to
  // sleep (which rebuilds it) saw no contacts for that step.
  plan_contacts(planned_contacts);
}

void World::Impl::plan_contacts(const ContactLayout& c) {
  planned_contacts = c;
  StepPlan& p = plan;
  p.contact_manifolds = c.manifolds;
  p.contact_points = c.points;
  p.contact_colors = c.colors;
  p.contact_overflow = c.overflow;
  p.contact_friction = (c.signatures & simd::kContactFriction) != 0;
  p.contact_rolling = (c.signatures & simd::kContactRolling) != 0;
  p.contact_restitution = c.restitution;
  // Take out what the last step's contacts added, then add what this step's need: the content
  // plan and plan_forces keep their own stages.
  std::vector<PlanStage>& stages = p.stages;
  for (PlanStage s : contact_stages) {
    stages.erase(std::remove(stages.begin(), stages.end(), s), stages.end());
  }
  contact_stages.clear();
  if (c.manifolds == 0) return;
  const auto add = [&](bool on, PlanStage stage) {
    if (!on || p.runs(stage)) return;
    // Stages are listed in enum order.
    stages.insert(std::find_if(stages.begin(), stages.end(), [&](PlanStage s) { return s > stage; }),
                  stage);
    contact_stages.push_back(stage);
  };
  add(true, PlanStage::PrepareContacts);
  add(settings.warm_start, PlanStage::WarmStart);
  add(!settings.warm_start, PlanStage::ClearImpulses);
  add(true, PlanStage::Solve);
  add(settings.relax_iterations > 0, PlanStage::Relax);
  add(c.restitution, PlanStage::Restitution);
}

const StepPlan& World::step_plan() const {
  impl_->build_plan();
  return impl_->plan;
}

bool StepPlan::runs(PlanStage stage) const {
  return std::find(stages.begin(), stages.end(), stage) != stages.end();
}

const char* plan_stage_name(PlanStage stage) {
  switch (stage) {
    case PlanStage::PrepareBodies:
      return "prepare_bodies";
    case PlanStage::PrepareJoints:
      return "prepare_joints";
    case PlanStage::PrepareContacts:
      return "prepare_contacts";
    case PlanStage::Gravity:
      return "gravity";
    case PlanStage::Damping:
      return "damping";
    case PlanStage::Forces:
      return "forces";
    case PlanStage::SpinLimit:
      return "spin_limit";
    case PlanStage::WarmStart:
      return "warm_start";
    case PlanStage::ClearImpulses:
      return "clear_impulses";
    case PlanStage::Solve:
      return "solve";
    case PlanStage::TreeSolve:
      return "tree_solve";
    case PlanStage::TreeRelax:
      return "tree_relax";
    case PlanStage::IntegratePositions:
      return "integrate_positions";
    case PlanStage::Relax:
      return "relax";
    case PlanStage::Restitution:
      return "restitution";
    case PlanStage::Store:
      return "store";
  }
  return "?";
}

const char* solver_mode_name(SolverMode mode) {
  switch (mode) {
    case SolverMode::Iterative:
      return "iterative";
    case SolverMode::DirectForTrees:
      return "direct-for-trees";
    case SolverMode::Auto:
      return "auto";
  }
  return "?";
}

const char* spring_row_name(SpringRow row) {
  switch (row) {
    case SpringRow::Any:
      return "any";
    case SpringRow::Rigid:
      return "rigid";
    case SpringRow::Soft:
      return "soft";
    case SpringRow::Free:
      return "free";
  }
  return "?";
}

}  // namespace softstep
