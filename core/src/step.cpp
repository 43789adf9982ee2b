// One step of Soft Step (DESIGN.md, "One step"):
//   prepare: anchors, effective masses, softness
//   per sub-step: integrate velocities, warm start, solve (soft, biased),
//                 integrate positions, relax (rigid, no bias)
//   store: write the double-precision poses and velocities back
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include "contacts/contact_validation.hpp"
#include "elapsed_ms.hpp"
#include "recording/recorder.hpp"
#include "solver/team.hpp"
#include "validation.hpp"
#include "world_impl.hpp"

namespace softstep {

namespace {

// A rigid row is a stiff spring while solving; a quarter of the sub-step rate keeps it
// well inside what one Gauss-Seidel pass can follow without overshoot.
double rigid_solve_hertz(const WorldSettings& s, float h) {
  return std::min(s.rigid_hertz, 0.25 / static_cast<double>(h));
}

// A joint's violated limit (a revolute's or swing-twist's angle, a slider's or wheel's
// travel) solves at twice the rigid rows' frequency, capped at half the sub-step rate. Such a
// limit carries what the bodies beyond it weigh on the effective mass of only the two bodies
// it joins, which for an angle is their inertia about their own centres: a hanging ragdoll's
// lower spine holds the upper body's ~80 N m on 0.026 kg m^2 and gave way by load / (m_eff
// omega^2), 1.15 degrees, at the rigid 60 Hz; at 120 Hz a quarter of it. Twice the rigid
// frequency is the ratio Box2D v3 keeps between its joints and its contacts. A limit pushes
// only, so a stiffer one lets go rather than pull back. The distance joint's length limits
// (ropes) keep the rigid softness: their load sits on the masses themselves.
double limit_solve_hertz(const WorldSettings& s, float h) {
  return std::min(2.0 * s.rigid_hertz, 0.5 / static_cast<double>(h));
}

simd::SubstepContext make_context(const WorldSettings& s, float h) {
  simd::SubstepContext ctx;
  ctx.h = h;
  ctx.inv_h = 1.0f / h;
  const double hertz = rigid_solve_hertz(s, h);
  ctx.rigid =
      simd::make_softness(static_cast<float>(hertz), static_cast<float>(s.rigid_damping_ratio), h);
  ctx.limit = simd::make_softness(static_cast<float>(limit_solve_hertz(s, h)),
                                 static_cast<float>(s.rigid_damping_ratio), h);
  // Undamped (rigid_damping_ratio 0) at the lowest frequency, a = (h omega)^2 reaches 7e-16
  // and 1/a times a lock's effective mass (up to the largest inertia, 1e24) left float. Where
  // 1/a > 1e13 the row's mass_scale a / (1 + a) is below 1e-13: it applies nothing either way.
  ctx.rigid.feedback = std::min(ctx.rigid.feedback, 1e13f);
  ctx.limit.feedback = std::min(ctx.limit.feedback, 1e13f);
  ctx.max_correction_speed = static_cast<float>(s.max_correction_speed);
  ctx.max_linear_speed = static_cast<float>(s.max_linear_speed);
  // Rounded to float before dividing, as the constant it replaced was: pi/4 gives the same
  // bound bit for bit.
  ctx.max_angular_speed = static_cast<float>(s.max_rotation_per_substep) / h;
  return ctx;
}

// Threads for this step. One when the setting says so, or when the work is too small to
// share: below a few thousand bodies and joints a step takes tens of microseconds, and a
// barrier per colour per stage (0.4-1 us each on an idle machine, TOOLCHAIN.md) costs more
// than the second core gives.
//
// Otherwise whichever of one thread or all ran recent steps faster (thread_policy.hpp). When
// another process holds a core, a step shorter than a scheduler time slice waits milliseconds
// at a barrier whenever one of its threads is descheduled: a 10,000-link step took 5x longer
// on two threads than on one. Results are bit-identical for any count, so switching never
// changes the simulation.
struct ThreadChoice {
  int threads;
  bool by_policy;  // the policy chose: it learns from this step's time
};
ThreadChoice step_threads(World::Impl& w) {
  constexpr std::size_t kMinWorkToShare = 4096;
  static const int machine_cores = std::max(1, omp_get_num_procs());
  const int allowed = w.settings.threads == 0 ? machine_cores : w.settings.threads;
  if (w.settings.fixed_threads) return {allowed, false};  // the user's count, not the policy's
  // An exactly solved joint (WorldSettings::solver) costs about five iterative ones, its rows
  // counted: a factor and two solves of its island each sub-step (README, "Rigid means
  // rigid"). The 1,000-link whip's exact step (about 1 ms, one island that two threads share)
  // is work enough; its iterative one (0.2 ms) is not.
  constexpr std::size_t kExactJointExtraWork = 4;
  // Sleeping bodies and joints are no work.
  const std::size_t work = w.solver_bodies.movable.size() + w.plan.rows_per_pass / 3 +
                           w.planned_contacts.points + kExactJointExtraWork * w.plan.tree_joints;
  if (allowed <= 1 || work < kMinWorkToShare) return {1, false};
  return {w.thread_policy.all_threads() ? allowed : 1, true};
}

// A step's threads on the host's job system: workers 1 .. n-1 are enqueued, the calling
// thread is worker 0, and finish waits for each. Every worker runs the same stages on the same
// Share as under OpenMP, so the result is the same bit for bit.
template <class Run>
void run_on_host_tasks(const TaskCallbacks& tasks, int threads, Run& run) {
  solver::StepBarrier barrier(threads);
  struct Job {
    Run* run;
    solver::StepBarrier* barrier;
    int threads;
  } job{&run, &barrier, threads};
  const TaskCallbacks::Task task = [](int worker, void* context) {
    Job& j = *static_cast<Job*>(context);
    (*j.run)(solver::Share{worker, j.threads, nullptr, j.barrier});
  };
  std::vector<void*> handles;
  for (int worker = 1; worker < threads; ++worker) {
    handles.push_back(tasks.enqueue(task, worker, &job, tasks.user_context));
  }
  run(solver::Share{0, threads, nullptr, &barrier});
  for (void* handle : handles) tasks.finish(handle, tasks.user_context);
}

// Runs run(share) on `threads` threads: the caller alone, the host's job system when it gave
// one (set_task_callbacks), or an OpenMP team. Returns how many ran it: an OpenMP team may come
// out smaller than asked (OMP_THREAD_LIMIT, a step called inside a parallel region), and the
// profile reports the threads that worked, not the count asked for.
template <class Run>
int run_team(const World::Impl& w, int threads, Run& run) {
  if (threads == 1) {
    run(solver::Share{});
    return 1;
  }
  if (w.tasks.enqueue != nullptr) {
    run_on_host_tasks(w.tasks, threads, run);
    return threads;
  }
  // The barrier is sized by the first thread to know the team's size, before anyone uses it.
  std::optional<solver::StepBarrier> barrier;
  int team = 1;
#pragma omp parallel num_threads(threads)
  {
#pragma omp single
    {
      team = omp_get_num_threads();
      barrier.emplace(team);
    }
    run(solver::Share{omp_get_thread_num(), omp_get_num_threads(), nullptr, &*barrier});
  }
  return team;
}

// Below this many manifolds the checks' scan stays on the caller: 4,096 take about 0.12 ms on
// one thread (the pyramid's 14,950: 0.45 ms), and waking a second thread costs tens of
// microseconds.
constexpr std::size_t kMinManifoldsToShare = 4096;

}  // namespace

// The geometric inertia's time scale t: the sub-step, but never less than the default one
// (1/240 s: 60 Hz, 4 sub-steps). The inertia added, t^2 sum(|F| |r|), keeps a link's
// alignment mode near 1/t; with t = h, finer sub-steps shrank it with h^2, and the "tiny
// inertia" hard case (20 links of inertia x 1e-6 hanging at 30 degrees), whose worst gap
// settles to 3 mm at 4 sub-steps, fell apart at 16 (gaps of 0.5-1.2 m, 131 m/s) and blew up
// at 64: its links turned about a radian per sub-step whatever the sub-step (even one
// sub-step per step of 1/960 s opened 0.34 m). Floored, it holds within 4 mm at 8, 16 and
// 64 sub-steps (2026-11-26). In float, as h is: the default sub-step, float(1/60 / 4), is
// the floor bit for bit, so default trajectories are unchanged.
constexpr float kGeometricTimeFloor = 1.0f / 240.0f;

bool World::Impl::geometric_inertia_applies(double impulse_substep) const {
  // A world without awake joints or with the setting off pays no pass.
  return settings.geometric_stiffness && impulse_substep > 0.0 && !plan.kernels.empty();
}

void World::Impl::plan_geometric_inertia(double impulse_substep, bool refresh) {
  extra_inertia_on = geometric_inertia_applies(impulse_substep);
  if ((extra_inertia_on || refresh) && extra_inertia.size() != bodies.size()) {
    extra_inertia.assign(bodies.size(), 0.0);
  }
}

void World::Impl::geometric_inertia(float h, double impulse_substep,
                                    const solver::Share& share) {
  if (!geometric_inertia_applies(impulse_substep)) return;
  // Only the awake bodies' entries are cleared and read: a step costs nothing for sleeping
  // ones.
  const solver::Slice mine = solver::slice_of(solver_bodies.movable.size(), share);
  for (std::size_t i = mine.begin; i < mine.end; ++i) extra_inertia[solver_bodies.movable[i]] = 0.0;
  solver::team_barrier(share);
  // Read by the mass records, after the barrier that ends the sums.
  if (share.thread == 0) extra_inertia_on = true;
  // |force| = |impulse of a sub-step| / that sub-step
  const double t = std::max(h, kGeometricTimeFloor);
  lane_solver->accumulate_geometric_inertia(joints, bodies, dynamic_body, t * t / impulse_substep,
                                            extra_inertia, share);
}

void World::Impl::list_bodies() {
  SolverBodies& sb = solver_bodies;
  constexpr int kBlock = solver::kBodyBlock;
  const std::size_t records = (bodies.size() + 1 + kBlock - 1) / kBlock * kBlock;
  sb.velocity.resize(records);
  sb.delta.resize(records);
  sb.mass.resize(records);
  sb.force.resize(records);
  sb.movable.clear();
  sb.blocks.clear();
  dynamic_body.resize(bodies.size());
  for (std::uint32_t s = 0; s < bodies.size(); ++s) {
    const BodySlot& b = bodies[s];
    dynamic_body[s] = b.alive && b.type == BodyType::Dynamic ? 1 : 0;
    if (b.alive && b.type != BodyType::Static && !b.asleep) {
      sb.movable.push_back(s);
      const std::int32_t block = static_cast<std::int32_t>(s + 1) / kBlock * kBlock;
      if (sb.blocks.empty() || sb.blocks.back() != block) sb.blocks.push_back(block);
    } else {
      // Integrated alongside awake bodies of its block: it must stay exactly where it is.
      sb.velocity[s + 1] = simd::VelocityRecord{};
      sb.delta[s + 1] = simd::DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0};
      sb.mass[s + 1] = simd::MassRecord{};
      sb.force[s + 1] = simd::ForceRecord{};
    }
  }
  sb.velocity[0] = simd::VelocityRecord{};
  sb.delta[0] = simd::DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0};
  sb.mass[0] = simd::MassRecord{};
  sb.force[0] = simd::ForceRecord{};
  for (std::size_t i = bodies.size() + 1; i < records; ++i) {
    sb.velocity[i] = simd::VelocityRecord{};
    sb.delta[i] = simd::DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0};
    sb.mass[i] = simd::MassRecord{};
    sb.force[i] = simd::ForceRecord{};
  }
  bodies_listed = true;
}

namespace {

// The solver's mass record of a dynamic body whose inertia is raised by `extra` (kg m^2) on the
// diagonal, in world axes.
simd::MassRecord mass_record(const BodySlot& b, double extra) {
  const Eigen::Matrix3d r = b.orientation.toRotationMatrix();
  Eigen::Matrix3d inv_i = r * b.inverse_inertia * r.transpose();
  if (extra > 0.0) {
    // inverse(R I R^T + c 1) = R inverse(I + c 1) R^T
    const Eigen::Matrix3d inv_body =
        b.diagonal_inertia
            ? Eigen::Matrix3d(
                  (b.inertia.diagonal().array() + extra).inverse().matrix().asDiagonal())
            : Eigen::Matrix3d((b.inertia + extra * Eigen::Matrix3d::Identity()).inverse());
    inv_i = r * inv_body * r.transpose();
  }
  return {static_cast<float>(1.0 / b.mass),
          {static_cast<float>(inv_i(0, 0)), static_cast<float>(inv_i(1, 1)),
           static_cast<float>(inv_i(2, 2)), static_cast<float>(inv_i(0, 1)),
           static_cast<float>(inv_i(0, 2)), static_cast<float>(inv_i(1, 2))},
          0.0f};
}

}  // namespace

void World::Impl::refresh_inertia(const solver::Share& share) {
  SolverBodies& sb = solver_bodies;
  const solver::Slice mine = solver::slice_of(sb.movable.size(), share);
  for (std::size_t index = mine.begin; index < mine.end; ++index) {
    const std::uint32_t s = sb.movable[index];
    if (bodies[s].type != BodyType::Dynamic) continue;
    sb.mass[s + 1] = mass_record(bodies[s], extra_inertia_on ? extra_inertia[s] : 0.0);
  }
}

void World::Impl::prepare_bodies(float h, const solver::Share& share) {
  SolverBodies& sb = solver_bodies;
  const bool forces = plan.forces;
  const solver::Slice mine = solver::slice_of(sb.movable.size(), share);
  for (std::size_t index = mine.begin; index < mine.end; ++index) {
    const std::uint32_t s = sb.movable[index];
    const BodySlot& b = bodies[s];
    const std::size_t i = s + 1;
    simd::VelocityRecord& v = sb.velocity[i];
    for (int k = 0; k < 3; ++k) {
      v.v[k] = static_cast<float>(b.linear_velocity[k]);
      v.w[k] = static_cast<float>(b.angular_velocity[k]);
    }
    sb.delta[i] = simd::DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0};
    simd::MassRecord& m = sb.mass[i];
    simd::ForceRecord& f = sb.force[i];
    if (b.type == BodyType::Dynamic) {
      m = mass_record(b, extra_inertia_on ? extra_inertia[s] : 0.0);
      Eigen::Vector3d g = settings.gravity * b.gravity_scale;
      Eigen::Vector3d alpha = Eigen::Vector3d::Zero();
      if (forces) {  // the applied force and torque, with the body's own inertia
        g += b.force / b.mass;
        const Eigen::Matrix3d r = b.orientation.toRotationMatrix();
        alpha = r * (b.inverse_inertia * (r.transpose() * b.torque));
      }
      f = {{static_cast<float>(g.x()), static_cast<float>(g.y()), static_cast<float>(g.z())},
           static_cast<float>(1.0 / (1.0 + h * b.linear_damping)),
           static_cast<float>(1.0 / (1.0 + h * b.angular_damping)),
           {static_cast<float>(alpha.x()), static_cast<float>(alpha.y()),
            static_cast<float>(alpha.z())}};
    } else {
      m = simd::MassRecord{};
      f = simd::ForceRecord{{0, 0, 0}, 1.0f, 1.0f, {0, 0, 0}};
    }
  }
}

bool World::Impl::finalize_bodies(const solver::Share& share, const RestTest& rest) {
  SolverBodies& sb = solver_bodies;
  const solver::Slice mine = solver::slice_of(sb.movable.size(), share);
  bool some_ready = false;
  for (std::size_t index = mine.begin; index < mine.end; ++index) {
    const std::uint32_t s = sb.movable[index];
    BodySlot& b = bodies[s];
    const simd::VelocityRecord& v = sb.velocity[s + 1];
    const simd::DeltaRecord& d = sb.delta[s + 1];
    b.position += Eigen::Vector3d(d.dp[0], d.dp[1], d.dp[2]);
    b.step_moved2 = d.dp[0] * d.dp[0] + d.dp[1] * d.dp[1] + d.dp[2] * d.dp[2];
    b.step_turned2 = d.dq[0] * d.dq[0] + d.dq[1] * d.dq[1] + d.dq[2] * d.dq[2];
    const Eigen::Quaterniond dq(d.dq[3], d.dq[0], d.dq[1], d.dq[2]);
    b.orientation = (dq * b.orientation).normalized();
    // A kinematic body keeps the velocity the user gave it, not its float copy.
    if (b.type == BodyType::Dynamic) {
      b.linear_velocity = Eigen::Vector3d(v.v[0], v.v[1], v.v[2]);
      b.angular_velocity = Eigen::Vector3d(v.w[0], v.w[1], v.w[2]);
    }
    if (rest.on) some_ready |= update_rest_time(b, rest);
  }
  return some_ready;
}

void World::step(double dt) {
  step(dt, {});
}

const std::vector<ContactReading>& World::contact_readings() const {
  impl_->settle_contact_readings();
  return impl_->contact_readings;
}

namespace {

// A contact between a sleeping body and an awake dynamic one wakes the sleeper (its island
// was resting on, or is being hit by, something that moves). True if any island woke.
bool wake_touched(World::Impl& w, std::span<const ContactManifold> contacts) {
  const auto moving = [&](std::uint32_t s) {
    return w.bodies[s].type == BodyType::Dynamic && !w.bodies[s].asleep;
  };
  bool woke = false;
  for (const ContactManifold& m : contacts) {
    const std::uint32_t a = m.body_a.index, b = m.body_b.index;
    if (w.bodies[a].asleep && moving(b)) {
      w.touch(a);
      woke = true;
    }
    if (w.bodies[b].asleep && moving(a)) {
      w.touch(b);
      woke = true;
    }
  }
  return woke;
}

}  // namespace

void World::step(double dt, std::span<const ContactManifold> contacts) {
  Impl& w = *impl_;
  const auto call_start = std::chrono::steady_clock::now();
  if (!(std::isfinite(dt) && dt > 0.0)) {
    validation::reject("step", "dt", validation::format(dt), "must be finite and > 0 s");
  }
  const WorldSettings& s = w.settings;
  const double substep = dt / s.substeps;
  if (!(substep >= validation::kMinSubstep && substep <= validation::kMaxSubstep)) {
    validation::reject("step", "dt", validation::format(dt),
                       "dt / substeps must be a sub-step in [" +
                           validation::format(validation::kMinSubstep) + ", " +
                           validation::format(validation::kMaxSubstep) + "] s");
  }
  const float h = static_cast<float>(substep);
  const auto check_start = std::chrono::steady_clock::now();
  ContactSolver& contact_solver = *w.contact_solver;
  ContactStep contact_step{contacts,     &w.bodies,       &w.contact_cache, &w.contact_cache_next,
                           s.warm_start, w.bodies_version};
  // The checks run on the threads the step would take now (judged by last step's plan and
  // layout: the count changes nothing in the result). With more than one, the second thread
  // lays the contacts out while the others check, then joins them. On the pyramid's 14,950
  // manifolds (two threads, Zen 4 host, 2026-11-28, 8 runs alternated) the step took 3.79 ms
  // against 4.01 with the checks and then the load on the caller alone (every run faster,
  // median 1.08x); with the caller laying out instead, 4.41 against 4.04, its `prepare` the
  // slower by 0.13 ms: the packing that follows reads the manifolds the caller has checked,
  // so the caller keeps reading them while the worker, cold after the caller's collision,
  // takes the layout, which touches one line of each. The layout holds unless a contact
  // wakes an island (below).
  // A scene whose contacts asked for last step's layout again (same bodies, point counts and
  // rows: a stack at rest) likely does so once more: then no thread lays out beside, every
  // thread checks, the checks compare each manifold's layout input with the last layout's as
  // they read it, and the load keeps the layout when all match (same_layout_inputs). On the
  // pyramid (two threads, Zen 4 host, 2026-11-28 05:30, three ways alternated step by step in
  // one process, 5 runs of 300 steps, a slow hour): the step took 1.02-1.10x (median 1.07x)
  // as long with the worker laying out beside the checks as with every thread checking and
  // the layout kept, and 1.01-1.07x (1.03x) with the caller checking alone and the layout kept;
  // at 07:05 the same alternation gave 0.98-1.02x (1.00x) and 1.01-1.12x (1.05x): every thread
  // checking is at least as fast, by how much moves with the hour.
  const int check_threads = contacts.size() >= kMinManifoldsToShare ? step_threads(w).threads : 1;
  const ContactLayoutInput* last_layout =
      contact_solver.layout_inputs(w.bodies_version, contacts.size());
  const bool expect_same_layout = last_layout != nullptr && contact_solver.layout().same_inputs;
  const bool lay_out_beside = check_threads > 1 && !expect_same_layout;
  std::atomic<bool> laid_out_beside{false};
  bool same_layout_inputs = false;
  int check_team = 1;
  {
    // The layout beside the checks rewrites the inputs they would compare with.
    validation::ContactChecks checks(w, contacts, lay_out_beside ? nullptr : last_layout);
    const auto check = [&](const solver::Share& share) {
      if (lay_out_beside && share.thread == 1 && contact_solver.load(contact_step)) {
        laid_out_beside.store(true, std::memory_order_relaxed);
      }
      checks.scan();
    };
    check_team = run_team(w, check_threads, check);
    checks.finish("step", w.contact_cache_next);
    same_layout_inputs = checks.same_layout_inputs();
  }
  const auto checked = std::chrono::steady_clock::now();
  const bool woke = wake_touched(w, contacts);
  // A step that colours and packs, or lists the bodies anew, first touches fresh memory: its
  // time says nothing about the thread count.
  const bool fresh_content = !w.joints_packed || !w.bodies_listed;
  w.build_plan();
  const simd::SubstepContext ctx = make_context(s, h);
  const bool load_alone = !laid_out_beside.load(std::memory_order_relaxed) || woke;
  if (load_alone) {
    contact_step.bodies_version = w.bodies_version;         // a wake changed it: no layout kept
    contact_solver.load(contact_step, same_layout_inputs);  // checked: it lays out every one
  }
  w.plan_contacts(contact_solver.layout());
  if (!w.trees.empty()) w.trees.mark_contacts(contacts);
  const simd::ContactContext contact_ctx = make_contact_context(s.contact, h);
  const bool friction_while_solving = contact_friction_while_solving(s);
  // Contacts run beside the joints in the same stages: with contacts, the solve stages run
  // even when no joint needs them; restitution only when some contact asks for it.
  const bool has_contacts = !contact_solver.empty();
  const bool restitution = has_contacts && contact_solver.layout().restitution;
  // The geometric inertia from the last step's impulses, summed in the team before the
  // bodies are prepared.
  const double inertia_substep = w.last_substep;
  // New joints have no force yet, so their bodies got no geometric inertia from them: a link of
  // tiny inertia then spins through the whole first step (0.5 m joint error in the "tiny
  // inertia" hard case). The first sub-step's impulses are a force; the inertia is recomputed
  // from them before the second sub-step (0.15 m). Probing the first sub-step and restarting
  // it with that inertia was tried, and did worse (0.35 m). The refresh reaches the joints'
  // rows only: the contacts' lanes keep the step-start inertia the contact prepare turned into
  // each manifold's frame (contact_kernel.hpp), their effective masses and impulses alike,
  // for the rest of that step. Sub-steps finer than
  // kGeometricTimeFloor recompute it before every later sub-step of that step: one sub-step's
  // impulses while the tension builds are too small a force (at 64 sub-steps the case blew
  // up with the floor alone). At the default sub-step and coarser, doing so measured worse
  // (0.25 m against 0.15), so it stays once.
  const bool refresh_inertia = w.joints_without_history && s.geometric_stiffness &&
                               s.substeps > 1 && !w.plan.kernels.empty();
  const bool refresh_every_substep = refresh_inertia && h < kGeometricTimeFloor;
  const auto refreshes_before = [&](int sub) {
    return sub >= 1 && refresh_inertia && (sub == 1 || refresh_every_substep);
  };
  w.plan_geometric_inertia(inertia_substep, refresh_inertia);
  const simd::BodyArrays arrays = w.solver_bodies.arrays();
  LaneSolver& solver = *w.lane_solver;
  // What this step runs: the plan's stages, nothing else.
  std::array<bool, kPlanStageCount> runs{};
  for (PlanStage p : w.plan.stages) runs[static_cast<std::size_t>(p)] = true;
  const auto planned = [&](PlanStage p) { return runs[static_cast<std::size_t>(p)]; };
  // The stages the joints run: planned for them, not only added for the contacts
  // (plan_contacts). Through planned() alone, a world whose joints are all solved exactly ran
  // the joints' warm start, solve and relax whenever it had contacts, which the plan had left
  // out (TreeContacts.ChainLyingOnTheGroundRestsWithRigidJointsAndCarriesItsWeight fails so).
  std::array<bool, kPlanStageCount> joint_runs = runs;
  for (PlanStage p : w.contact_stages) joint_runs[static_cast<std::size_t>(p)] = false;
  const auto joints_run = [&](PlanStage p) { return joint_runs[static_cast<std::size_t>(p)]; };
  // Applied forces ride on the gravity term (force / mass), torques on their own.
  const bool torque = planned(PlanStage::Forces);
  const bool gravity = planned(PlanStage::Gravity) || torque;
  const bool damping = planned(PlanStage::Damping);
  const bool capturing = w.capturing;
  const Impl::RestTest rest = w.rest_test(dt);
  std::atomic<bool> some_ready{false};  // read after the team has joined
  // Tree islands stepped whole (tree_solver.hpp, whole_substeps): 100 chains of 1,000 links
  // 1.30x faster on one thread and 1.36x on two than stage by stage, whose every pass streamed
  // the islands' 140 MB of state through memory; the profile counts it all as `solve`.
  const bool whole = w.plan.tree_islands_whole && !has_contacts && !capturing && !refresh_inertia;
  if (capturing) w.capture_step_start(h, rigid_solve_hertz(s, h));

  // Every thread runs every stage on its share; team_barrier orders the stages.
  const bool profiling = w.profiling;
  const auto step_start = std::chrono::steady_clock::now();
  const auto since_start = [&] {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - step_start)
        .count();
  };
  std::vector<std::vector<StageEvent>> events;
  std::vector<double> waits;
  const auto run = [&](solver::Share share) {
    if (profiling) share.barrier_wait_us = &waits[static_cast<std::size_t>(share.thread)];
    // Runs one stage, recording its span on this thread when profiling.
    const auto stage = [&](Stage which, auto&& work) {
      if (!profiling) {
        work();
        return;
      }
      const double begin = since_start();
      work();
      events[static_cast<std::size_t>(share.thread)].push_back({which, begin, since_start()});
    };
    if (planned(PlanStage::PrepareBodies) || planned(PlanStage::PrepareJoints)) {
      stage(Stage::Prepare, [&] {
        // The contacts' lanes; the barriers below order them before the contacts' prepare.
        if (has_contacts) contact_solver.pack(share);
        w.geometric_inertia(h, inertia_substep, share);
        w.prepare_bodies(h, share);
        solver::team_barrier(share);
        if (planned(PlanStage::PrepareJoints)) {
          solver.prepare(w.joints, w.bodies, arrays, ctx, share);
          solver::team_barrier(share);
        }
        if (has_contacts) {
          contact_solver.prepare(arrays, ctx, share);
          solver::team_barrier(share);
        }
      });
    }
    if (whole) {
      stage(Stage::Solve, [&] {
        solver.clear_impulses(share);
        solver::team_barrier(share);
        w.trees.whole_substeps(w.joints, w.bodies, w.solver_bodies, solver, ctx,
                               {.substeps = s.substeps,
                                .gravity = gravity,
                                .damping = damping,
                                .torque = torque,
                                .relax = planned(PlanStage::TreeRelax)},
                               share);
        solver::team_barrier(share);
      });
    }
    for (int sub = 0; sub < s.substeps && !whole; ++sub) {
      if (planned(PlanStage::SpinLimit)) {
        stage(Stage::IntegrateVelocities, [&] {
          if (refreshes_before(sub)) {
            w.geometric_inertia(h, h, share);
            w.refresh_inertia(share);  // integrate_velocities reads no mass record
          }
          solver.integrate_velocities(w.solver_bodies, ctx, gravity, damping, torque, share);
          solver::team_barrier(share);
        });
      }
      if (capturing && sub == 0) {
        if (share.thread == 0) w.capture_before_solve();
        solver::team_barrier(share);  // the warm start writes the velocities just copied
      }
      if (planned(PlanStage::WarmStart) || planned(PlanStage::ClearImpulses) || has_contacts) {
        stage(Stage::WarmStart, [&] {
          if (joints_run(PlanStage::WarmStart)) {
            solver.warm_start(arrays, ctx, share);
          } else if (joints_run(PlanStage::ClearImpulses)) {
            solver.clear_impulses(share);
            solver::team_barrier(share);
          }
          // As the joints: without warm starting each sub-step starts from zero impulse (the
          // last sub-step's, kept but not applied again, would be clamped and read as if it
          // were this sub-step's).
          if (has_contacts && s.warm_start) {
            contact_solver.warm_start(arrays, ctx, contact_ctx, share);
          } else if (has_contacts) {
            contact_solver.clear_impulses(share);
            solver::team_barrier(share);
          }
        });
      }
      if (planned(PlanStage::Solve) || has_contacts) {
        stage(Stage::Solve, [&] {
          for (int i = 0; i < s.solve_iterations; ++i) {
            if (joints_run(PlanStage::Solve)) solver.solve(arrays, ctx, share);
            if (has_contacts) {
              contact_solver.solve(arrays, ctx, contact_ctx, friction_while_solving, share);
            }
          }
        });
      }
      if (planned(PlanStage::TreeSolve)) {
        stage(Stage::Solve, [&] {
          // The masses change at the sub-steps where the inertia is refreshed (a new factor),
          // and at a step's start (the pass re-reads them, TreeSolver::Pass). A capture
          // compares the first sub-step's solve with the reference solve of its own system:
          // with a factor of its own.
          const bool reuse = sub == 0 ? !capturing : !refreshes_before(sub);
          w.trees.pass(w.joints, w.bodies, w.solver_bodies, solver, ctx,
                       {.with_bias = true, .step_start = sub == 0, .reuse_relax_factor = reuse},
                       share);
          solver::team_barrier(share);
        });
      }
      // The solve ended at a barrier, and until the next barrier no thread writes velocities
      // or impulses (positions move): thread 0 may read them.
      if (capturing && sub == 0 && share.thread == 0) w.capture_solved();
      if (planned(PlanStage::IntegratePositions)) {
        stage(Stage::IntegratePositions, [&] {
          solver.integrate_positions(w.solver_bodies, ctx, share);
          solver::team_barrier(share);
        });
      }
      if (planned(PlanStage::Relax) || (has_contacts && s.relax_iterations > 0)) {
        stage(Stage::Relax, [&] {
          for (int r = 0; r < s.relax_iterations; ++r) {
            if (joints_run(PlanStage::Relax)) solver.relax(arrays, ctx, share);
            if (has_contacts) contact_solver.relax(arrays, ctx, contact_ctx, share);
          }
        });
      }
      if (planned(PlanStage::TreeRelax)) {
        stage(Stage::Relax, [&] {
          // The next sub-step's solve pass folded into this one where nothing but the
          // velocity integration's additions (gravity, forces, torques; not damping, nor the
          // contact passes: an island with a damped body or in a contact does not fold,
          // TreeSolver::Pass::fold_next) changes the tree islands' velocities before it.
          const bool may_fold = !refreshes_before(sub + 1) && !joints_run(PlanStage::Solve) &&
                                !joints_run(PlanStage::WarmStart);
          w.trees.pass(w.joints, w.bodies, w.solver_bodies, solver, ctx,
                       solver::TreeSolver::Pass::relax(sub, s.substeps, may_fold, gravity, torque),
                       share);
          solver::team_barrier(share);
        });
      }
    }
    if (restitution) {
      stage(Stage::Restitution,
            [&] { contact_solver.restitute(arrays, ctx, contact_ctx, share); });
    }
    if (planned(PlanStage::Store)) {
      stage(Stage::Store, [&] {
        if (w.finalize_bodies(share, rest)) some_ready.store(true, std::memory_order_relaxed);
      });
    }
    // The contacts' impulses into the readings and the next cache: the last contact pass
    // ended at a barrier, and the bodies' store touches neither.
    if (!contacts.empty()) stage(Stage::Store, [&] { contact_solver.store(share); });
  };
  const ThreadChoice choice = step_threads(w);
  const int threads = choice.threads;
  if (profiling) {
    events.assign(static_cast<std::size_t>(threads), {});
    waits.assign(static_cast<std::size_t>(threads), 0.0);
  }
  const int team = run_team(w, threads, run);
  const double team_ms = since_start() * 1e-3;
  // A team smaller than the policy asked for did not run the step on the count it is judging.
  if (choice.by_policy) w.thread_policy.record(team_ms, fresh_content || team < threads);
  if (profiling) {
    StepProfile& p = w.profile;
    p.step_ms = team_ms + (load_alone ? contact_solver.layout().load_ms : 0.0);
    p.contact_load_beside_checks = !load_alone;
    p.contact_layout_kept = contact_solver.layout().kept;
    p.threads = team;
    p.thread_switches = w.thread_policy.switches();
    p.contact_load_ms = contact_solver.layout().load_ms;
    p.contact_check_ms = ms_between(check_start, checked);
    p.check_start_ms = ms_between(call_start, check_start);
    p.team_start_ms = ms_between(call_start, step_start);
    p.check_threads = check_team;
    p.stage_ms.fill(0.0);
    for (const StageEvent& e : events[0])
      p.stage_ms[static_cast<std::size_t>(e.stage)] += (e.end_us - e.start_us) * 1e-3;
    p.thread_events = std::move(events);
    p.barrier_wait_ms.clear();
    for (double us : waits) p.barrier_wait_ms.push_back(us * 1e-3);
  }
  w.contact_cache_next.become_current(w.contact_cache);
  w.contact_readings_pending = true;
  w.last_substep = h;
  w.joints_without_history = false;
  w.clear_forces();
  w.update_sleep(some_ready.load(std::memory_order_relaxed));
  if (w.recorder) w.recorder->step(dt, contacts, motion_hash());
  if (profiling) {
    const double call_ms = ms_since(call_start);
    w.profile.call_ms = call_ms;
    const double shared_checks_ms = check_team > 1 ? w.profile.contact_check_ms : 0.0;
    w.profile.serial_ms = std::max(0.0, call_ms - team_ms - shared_checks_ms);
  }
}

void World::set_task_callbacks(const TaskCallbacks& callbacks) {
  if ((callbacks.enqueue == nullptr) != (callbacks.finish == nullptr)) {
    validation::reject(
        "set_task_callbacks",
        callbacks.enqueue == nullptr ? "TaskCallbacks.enqueue" : "TaskCallbacks.finish", "nullptr",
        "enqueue and finish are given together (both nullptr: OpenMP)");
  }
  impl_->tasks = callbacks;
}

void World::set_profiling(bool on) {
  impl_->profiling = on;
}

const StepProfile& World::last_step_profile() const {
  return impl_->profile;
}

const char* stage_name(Stage stage) {
  switch (stage) {
    case Stage::Prepare:
      return "prepare";
    case Stage::IntegrateVelocities:
      return "integrate_velocities";
    case Stage::WarmStart:
      return "warm_start";
    case Stage::Solve:
      return "solve";
    case Stage::IntegratePositions:
      return "integrate_positions";
    case Stage::Relax:
      return "relax";
    case Stage::Store:
      return "store";
    case Stage::Restitution:
      return "restitution";
  }
  return "?";
}

SolverLayout World::solver_layout() const {
  const Impl& w = *impl_;
  const int lanes = w.lane_solver->lanes();
  const graph_coloring::ColoringStats stats = w.coloring.stats(lanes);
  SolverLayout layout;
  layout.simd = w.width;
  layout.lanes = lanes;
  layout.colors_used = stats.colors_used;
  for (int c = 0; c < graph_coloring::kColorCount; ++c) {
    if (stats.per_color[c] > 0) layout.joints_per_color.push_back(stats.per_color[c]);
  }
  layout.overflow_joints = stats.overflow;
  layout.lane_fill = stats.lane_fill;
  return layout;
}

}  // namespace softstep
