#include "solver/tree_solver.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <type_traits>

#include "softstep/contacts.hpp"
#include "solver/four_doubles.hpp"
#include "solver/team.hpp"
#include "world_impl.hpp"

namespace softstep::solver {

namespace {

// The joints the exact pass models: a rigid ball joint (3 rows) or a rigid distance joint
// (1 row; its limits are off when rigid, distance_joint.cpp).
bool exact_kind(const JointSlot& j) {
  if (j.type == JointType::Ball) return std::get<BallJointDef>(j.def).spring.is_rigid();
  if (j.type == JointType::Distance) return std::get<DistanceJointDef>(j.def).spring.is_rigid();
  return false;
}

LaneSolver::RecordRuns records_of(const auto& part) {
  return {part.record_runs, part.single_records};
}

bool moves(const BodySlot& b) {
  return b.type == BodyType::Dynamic;
}

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// A ball joint's rows against one body, sign [I, -skew(r)] (sign -1 on side a, +1 on side
// b), as the six columns of the col-major 3x6 block (three doubles and a zero each), built
// entry by entry: Eigen's comma initializer over an identity and a skew matrix was a twelfth
// of the whip's exact step.
struct BallColumns {
  FourDoubles column[6];
};

[[gnu::always_inline]] inline BallColumns ball_columns(double sign, const Eigen::Vector3d& r) {
  const double x = sign * r.x(), y = sign * r.y(), z = sign * r.z();
  BallColumns b;
  b.column[0] = FourDoubles{sign, 0.0, 0.0, 0.0};
  b.column[1] = FourDoubles{0.0, sign, 0.0, 0.0};
  b.column[2] = FourDoubles{0.0, 0.0, sign, 0.0};
  b.column[3] = FourDoubles{0.0, -z, y, 0.0};
  b.column[4] = FourDoubles{z, 0.0, -x, 0.0};
  b.column[5] = FourDoubles{-y, x, 0.0, 0.0};
  return b;
}

[[gnu::always_inline]] inline void store_columns(const BallColumns& b, Jac& jac) {
  for (int k = 0; k < 6; ++k) store3(jac.data() + 3 * k, b.column[k]);
}

// A ball joint's arms a = -s r (TreeJoint::arm) from the anchors' arms: r_a on side a (s = -1),
// -r_b on side b.
[[gnu::always_inline]] inline void store_arms(const Eigen::Vector3d& r_a,
                                              const Eigen::Vector3d& r_b, TreeJoint& t) {
  for (int k = 0; k < 3; ++k) {
    t.arm[0][k] = r_a[k];
    t.arm[1][k] = -r_b[k];
  }
}

// J v of a ball joint's rows s [I, -[r]x] on both sides (s = -1 on side a, +1 on side b),
// from the anchors' arms: (v_b + w_b x r_b) - (v_a + w_a x r_a), the relative velocity of the
// anchor points: a cross product a side, where each side's six columns, built first, were
// scaled and summed (the whip's exact step 0.422 -> 0.407 ms, Zen 5).
[[gnu::always_inline]] inline FourDoubles point_velocity(const FourDoubles& r, const Vec6& v) {
  return FourDoubles{v[0], v[1], v[2], 0.0} + cross(FourDoubles{v[3], v[4], v[5], 0.0}, r);
}
[[gnu::always_inline]] inline FourDoubles ball_times(const FourDoubles& r_a, const FourDoubles& r_b,
                                                     const Vec6& va, const Vec6& vb) {
  return point_velocity(r_b, vb) - point_velocity(r_a, va);
}

void fill_ball_rows(double sign, const Eigen::Vector3d& r, Jac& jac) {
  store_columns(ball_columns(sign, r), jac);
}

Vec6 velocity_of(const simd::VelocityRecord& v) {
  Vec6 x;
  x << v.v[0], v.v[1], v.v[2], v.w[0], v.w[1], v.w[2];
  return x;
}

// A body's pose now as the kernels see it: the step-start pose moved by the solver's delta.
struct PoseNow {
  Eigen::Vector3d dp;
  Eigen::Quaterniond dq;
};

PoseNow pose_now(const simd::DeltaRecord& d) {
  return {Eigen::Vector3d(d.dp[0], d.dp[1], d.dp[2]),
          Eigen::Quaterniond(d.dq[3], d.dq[0], d.dq[1], d.dq[2])};
}

// C of a joint whose anchors are `separation` apart (a distance joint's in row 0; padding 0;
// a distance joint without an axis has no row, so 0).
Eigen::Vector3d violation(const TreeJoint& t, double rest_length,
                          const Eigen::Vector3d& separation) {
  if (t.ball) return separation;
  const double length = separation.norm();
  return {length > 1e-9 ? length - rest_length : 0.0, 0.0, 0.0};
}

// How far the joint is from holding, m: |C|, and for a distance joint without an axis its
// rest length (it has no row to say so).
double violation_size(const TreeJoint& t, double rest_length, const Eigen::Vector3d& separation) {
  if (t.ball) return separation.norm();
  return std::abs(separation.norm() - rest_length);
}

// Moves the deltas of the bodies `part` lists (island-local indices into the island's body
// `slots`) by dx_of(b) (linear, then a first-order turn), not their velocities: the relax
// pass's position projection.
// The turn is q + (0, dw / 2) q, normalized, spelt out on the four coefficients (x, y, z, w as
// the record stores them): through Eigen's quaternion product and normalize() this loop was a
// third of the exact relax pass's own work (perf, the 1,000-link whip).
template <class Dx>
void move_positions(const std::vector<std::uint32_t>& part, const std::vector<std::uint32_t>& slots,
                    SolverBodies& sb, Dx dx_of) {
  for (const std::uint32_t b : part) {
    simd::DeltaRecord& d = sb.delta[slots[b] + 1];
    const Vec6 dx = dx_of(b);
    for (int k = 0; k < 3; ++k) d.dp[k] = static_cast<float>(double(d.dp[k]) + dx[k]);
    const double x = d.dq[0], y = d.dq[1], z = d.dq[2], w = d.dq[3];
    const double tx = 0.5 * dx[3], ty = 0.5 * dx[4], tz = 0.5 * dx[5];
    const FourDoubles moved = {x + (tx * w + (ty * z - tz * y)), y + (ty * w + (tz * x - tx * z)),
                               z + (tz * w + (tx * y - ty * x)), w - (tx * x + ty * y + tz * z)};
    const FourDoubles squares = moved * moved;
    const FourDoubles unit =
        moved / std::sqrt((squares[0] + squares[1]) + (squares[2] + squares[3]));
    for (int k = 0; k < 4; ++k) d.dq[k] = static_cast<float>(unit[k]);
  }
}

// Joint j's rows at anchors r_a, r_b that are `separation` apart.
void fill_jacobians(const Eigen::Vector3d& r_a, const Eigen::Vector3d& r_b,
                    const Eigen::Vector3d& separation, TreeJoint& t) {
  if (t.ball) {
    fill_ball_rows(-1.0, r_a, t.jacobian[0]);
    fill_ball_rows(1.0, r_b, t.jacobian[1]);
    store_arms(r_a, r_b, t);
    return;
  }
  const double length = separation.norm();
  t.jacobian[0].setZero();
  t.jacobian[1].setZero();
  t.gamma.setZero();
  if (length > 1e-9) {
    const Eigen::Vector3d n = separation / length;
    t.jacobian[0].block<1, 3>(0, 0) = -n.transpose();
    t.jacobian[0].block<1, 3>(0, 3) = -r_a.cross(n).transpose();
    t.jacobian[1].block<1, 3>(0, 0) = n.transpose();
    t.jacobian[1].block<1, 3>(0, 3) = r_b.cross(n).transpose();
  } else {
    // No axis: no row (as the kernel's normalize_or_zero). A unit softness keeps the joint's
    // block invertible; its impulse comes out 0.
    t.gamma(0, 0) = 1.0;
  }
}

// fill_jacobians, and J v for N pairs of the bodies' velocities (va[i], vb[i]); a ball joint's
// blocks only where `blocks` (TreeSystem::reads_blocks), its arms always. A ball joint's J v
// comes from its arms in registers (ball_times), never from a block just stored: read back,
// each column's two-double load waited for the two single stores it spans, which a store
// cannot forward (14 % of solve_island's samples on the whip, Zen 4).
template <int N>
[[gnu::always_inline]] inline void fill_jacobians_times(
    const Eigen::Vector3d& r_a, const Eigen::Vector3d& r_b, const Eigen::Vector3d& separation,
    const Vec6 (&va)[N], const Vec6 (&vb)[N], TreeJoint& t, FourDoubles (&jv)[N], bool blocks) {
  if (t.ball) {
    store_arms(r_a, r_b, t);
    if (blocks) {
      store_columns(ball_columns(-1.0, r_a), t.jacobian[0]);
      store_columns(ball_columns(1.0, r_b), t.jacobian[1]);
    }
    for (int i = 0; i < N; ++i)
      jv[i] = ball_times(load3(r_a.data()), load3(r_b.data()), va[i], vb[i]);
    return;
  }
  fill_jacobians(r_a, r_b, separation, t);
  for (int i = 0; i < N; ++i) {
    jv[i] = times_vector(t.jacobian[0], va[i]) + times_vector(t.jacobian[1], vb[i]);
  }
}

// J v of joint j's rows at anchors r_a, r_b (`separation` apart), the rows not stored: a solve
// pass that reuses a factor keeps that factor's Jacobians in the rows (Pass::reuse_relax_factor).
// A ball joint's as fill_jacobians_times forms them (the same bits).
FourDoubles jacobians_times(bool ball, const Eigen::Vector3d& r_a, const Eigen::Vector3d& r_b,
                            const Eigen::Vector3d& separation, const Vec6& va, const Vec6& vb) {
  if (ball) return ball_times(load3(r_a.data()), load3(r_b.data()), va, vb);
  TreeJoint rows;  // a distance joint's (TreeJoint::ball false)
  fill_jacobians(r_a, r_b, separation, rows);
  return times_vector(rows.jacobian[0], va) + times_vector(rows.jacobian[1], vb);
}

// More projections run where the first left a joint open by more than this: J dx = -C is
// linear, and an anchor of a link turning fast moves on an arc, not along its tangent. At most
// this many more per relax pass (each a factor and a solve; the whips need two).
constexpr double kProjectionTolerance = 1e-6;  // m
constexpr int kMaxExtraProjections = 2;

// An island is shared by two threads only from this size: a shared sub-step meets at eight
// barriers (about a microsecond each on an idle machine), a link's exact work is about a
// quarter microsecond a sub-step.
constexpr std::size_t kShareMinJoints = 256;

}  // namespace

void TreeSolver::Crew::sync() const {
  if (team != nullptr) team_barrier(*team);
}

TreeSolver::Crew TreeSolver::member_of(const Share& share) {
  Crew crew;
  crew.first_part = std::min(share.thread, 2);
  crew.end_part = std::min(share.thread + 1, 2);
  crew.lead = share.thread == 0;
  crew.team = &share;
  return crew;
}

bool TreeSolver::shared(const Island& island, int threads) const {
  return threads >= 2 && island.system.split() && island.joints.size() >= kShareMinJoints &&
         island.joints.size() * static_cast<std::size_t>(threads) > counts_.tree_joints;
}

void TreeSolver::build(SolverMode mode, const JointSlots& joints, const BodySlots& bodies,
                       const LaneSolver& lanes) {
  islands_.clear();
  island_of_slot_.assign(bodies.size(), -1);
  counts_ = {};
  if (mode == SolverMode::Iterative) return;
  // Islands of movable bodies over the awake joints, with a loop flag and an "only kinds the
  // exact pass models" flag per root.
  std::vector<std::uint32_t> parent(bodies.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<bool> loop(bodies.size(), false), other(bodies.size(), false);
  std::vector<std::uint32_t> awake;
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    const JointSlot& slot = joints[j];
    if (!slot.alive || !lanes.in_lanes(j)) continue;
    const bool a = moves(bodies[slot.body_a]), b = moves(bodies[slot.body_b]);
    if (!a && !b) continue;  // nothing to solve: no island
    awake.push_back(j);
    const std::uint32_t ra = find(parent, a ? slot.body_a : slot.body_b);
    const std::uint32_t rb = find(parent, b ? slot.body_b : slot.body_a);
    bool joined_loop = loop[ra] || loop[rb];
    bool joined_other = other[ra] || other[rb] || !exact_kind(slot);
    if (a && b && ra == rb) joined_loop = true;  // a second path between two bodies
    const std::uint32_t root = std::min(ra, rb);
    parent[std::max(ra, rb)] = root;
    loop[root] = joined_loop;
    other[root] = joined_other;
  }
  // Islands in order of their smallest body slot; members in slot order.
  std::vector<std::int32_t> island_of(bodies.size(), -1);
  std::vector<std::uint32_t> roots;
  for (std::uint32_t j : awake) {
    const JointSlot& slot = joints[j];
    const std::uint32_t body = moves(bodies[slot.body_a]) ? slot.body_a : slot.body_b;
    const std::uint32_t r = find(parent, body);
    if (island_of[r] == -1) {
      island_of[r] = static_cast<std::int32_t>(roots.size());
      roots.push_back(r);
    }
  }
  std::vector<Island> candidates(roots.size());
  std::vector<std::int32_t> local(bodies.size(), -1);
  for (std::uint32_t s = 0; s < bodies.size(); ++s) {
    if (!moves(bodies[s]) || bodies[s].asleep || !bodies[s].alive) continue;
    const std::uint32_t r = find(parent, s);
    if (island_of[r] < 0) continue;
    Island& island = candidates[static_cast<std::size_t>(island_of[r])];
    local[s] = static_cast<std::int32_t>(island.bodies.size());
    island.bodies.push_back(s);
  }
  for (std::uint32_t j : awake) {
    const JointSlot& slot = joints[j];
    const std::uint32_t body = moves(bodies[slot.body_a]) ? slot.body_a : slot.body_b;
    Island& island = candidates[static_cast<std::size_t>(island_of[find(parent, body)])];
    island.joints.push_back(j);
    TreeJoint t;
    t.body[0] = moves(bodies[slot.body_a]) ? local[slot.body_a] : -1;
    t.body[1] = moves(bodies[slot.body_b]) ? local[slot.body_b] : -1;
    t.rows = slot.type == JointType::Ball ? 3 : 1;
    t.ball = slot.type == JointType::Ball;  // its rows come from ball_columns
    island.rows.push_back(t);
    // Every awake joint has a row here, also of kinds whose island then stays iterative.
    island.rest_length.push_back(
        slot.type == JointType::Distance ? std::get<DistanceJointDef>(slot.def).rest_length : 0.0);
  }
  for (std::size_t i = 0; i < roots.size(); ++i) {
    Island& island = candidates[i];
    if (loop[roots[i]]) {
      ++counts_.loop_islands;
      continue;
    }
    if (other[roots[i]]) {
      ++counts_.other_islands;
      continue;
    }
    // One joint: a Gauss-Seidel pass is already its exact block solve.
    if (mode == SolverMode::Auto && island.joints.size() < 2) continue;
    if (!island.system.build(static_cast<std::uint32_t>(island.bodies.size()), island.rows)) {
      ++counts_.loop_islands;  // a loop through the ground: two joints to static or kinematic
      continue;
    }
    for (std::uint32_t b = 0; b < island.bodies.size(); ++b) {
      island.parts[island.system.body_part(b)].bodies.push_back(b);
      const BodySlot& body = bodies[island.bodies[b]];
      island.damped |= body.linear_damping > 0.0 || body.angular_damping > 0.0;
    }
    for (Part& part : island.parts) {
      // The part's bodies are in slot order: a run of kBodyBlock consecutive records is one
      // whose last is kBodyBlock - 1 past its first.
      const auto record = [&](std::size_t n) {
        return static_cast<std::int32_t>(island.bodies[part.bodies[n]] + 1);
      };
      std::size_t next = 0;
      while (next < part.bodies.size()) {
        const std::size_t last = next + kBodyBlock - 1;
        if (last < part.bodies.size() && record(last) == record(next) + kBodyBlock - 1) {
          part.record_runs.push_back(record(next));
          next += kBodyBlock;
        } else {
          part.single_records.push_back(record(next++));
        }
      }
    }
    for (std::uint32_t k = 0; k < island.joints.size(); ++k) {
      island.parts[island.system.joint_part(k)].joints.push_back(k);
    }
    island.inverse_mass.resize(island.bodies.size());
    island.dv.resize(island.bodies.size());
    island.dp.resize(island.joints.size());
    island.dv_pair.resize(island.bodies.size());
    island.dp_pair.resize(island.joints.size());
    island.dv_triple.resize(island.bodies.size());
    island.dp_triple.resize(island.joints.size());
    island.next_change.resize(island.joints.size());
    island.error.resize(island.joints.size());
    island.held_back.resize(island.joints.size());
    island.kept.resize(island.joints.size());
    island.anchor_a.resize(island.joints.size());
    island.anchor_b.resize(island.joints.size());
    island.offset.resize(island.joints.size());
    island.anchors.resize(island.joints.size());
    for (std::uint32_t j : island.joints) {
      const JointSlot& slot = joints[j];
      island.solver_a.push_back(solver_index(bodies[slot.body_a], slot.body_a));
      island.solver_b.push_back(solver_index(bodies[slot.body_b], slot.body_b));
    }
    ++counts_.tree_islands;
    if (island.system.split()) ++counts_.split_islands;
    counts_.tree_joints += island.joints.size();
    counts_.tree_bodies += island.bodies.size();
    for (const std::uint32_t slot : island.bodies) {
      island_of_slot_[slot] = static_cast<std::int32_t>(islands_.size());
    }
    islands_.push_back(std::move(island));
  }
}

void TreeSolver::mark_contacts(std::span<const ContactManifold> manifolds) {
  for (Island& island : islands_) island.contacted = false;
  const auto mark = [&](BodyId body) {
    // A body created since the islands were built is in none of them.
    if (body.index < island_of_slot_.size() && island_of_slot_[body.index] >= 0) {
      islands_[static_cast<std::size_t>(island_of_slot_[body.index])].contacted = true;
    }
  };
  for (const ContactManifold& m : manifolds) {
    mark(m.body_a);
    mark(m.body_b);
  }
}

void TreeSolver::pass(const JointSlots& joints, const BodySlots& bodies,
                      SolverBodies& solver_bodies, LaneSolver& lanes,
                      const simd::SubstepContext& ctx, Pass which, const Share& share) {
  // Islands are disjoint in bodies and joints: each thread solves its slice alone, after the
  // islands the team shares.
  const Crew crew = member_of(share);
  for (Island& island : islands_) {
    if (shared(island, share.threads)) {
      solve_island(island, joints, bodies, solver_bodies, lanes, ctx, which, crew);
    }
  }
  const Slice mine = slice_of(islands_.size(), share);
  for (std::size_t i = mine.begin; i < mine.end; ++i) {
    if (shared(islands_[i], share.threads)) continue;
    solve_island(islands_[i], joints, bodies, solver_bodies, lanes, ctx, which, alone());
  }
}

void TreeSolver::whole_substeps(const JointSlots& joints, const BodySlots& bodies, SolverBodies& sb,
                                LaneSolver& lanes, const simd::SubstepContext& ctx,
                                const Whole& whole, const Share& share) {
  const Crew crew = member_of(share);
  for (Island& island : islands_) {
    if (shared(island, share.threads))
      whole_island(island, joints, bodies, sb, lanes, ctx, whole, crew);
  }
  const Slice mine = slice_of(islands_.size(), share);
  for (std::size_t i = mine.begin; i < mine.end; ++i) {
    if (shared(islands_[i], share.threads)) continue;
    whole_island(islands_[i], joints, bodies, sb, lanes, ctx, whole, alone());
  }
}

void TreeSolver::whole_island(Island& island, const JointSlots& joints, const BodySlots& bodies,
                              SolverBodies& sb, LaneSolver& lanes, const simd::SubstepContext& ctx,
                              const Whole& whole, const Crew& crew) {
  for (int sub = 0; sub < whole.substeps; ++sub) {
    // The lanes' impulses were cleared once before (as at each sub-step's start when stepped
    // stage by stage): only the last sub-step's passes add theirs.
    const bool last = sub == whole.substeps - 1;
    for (int p = crew.first_part; p < crew.end_part; ++p) {
      lanes.integrate_velocities_of(sb, records_of(island.parts[p]), ctx, whole.gravity,
                                    whole.damping, whole.torque);
    }
    // After a folding relax pass the solve pass only hands over impulses: no barrier for it.
    if (!island.folded) crew.sync();  // a joint between the parts reads both bodies' velocities
    solve_island(island, joints, bodies, sb, lanes, ctx,
                 {.with_bias = true,
                  .step_start = sub == 0,
                  .reuse_relax_factor = true,
                  .add_impulses = last},
                 crew);
    for (int p = crew.first_part; p < crew.end_part; ++p) {
      lanes.integrate_positions_of(sb, records_of(island.parts[p]), ctx);
    }
    if (whole.relax) {
      crew.sync();  // and both bodies' positions
      // Nothing but the integration changes the velocities between (an island stepped whole);
      // an island with a damped body does not fold (Island::damped).
      Pass relax = Pass::relax(sub, whole.substeps, true, whole.gravity, whole.torque);
      relax.add_impulses = last;
      solve_island(island, joints, bodies, sb, lanes, ctx, relax, crew);
    }
  }
}

void TreeSolver::solve_island(Island& island, const JointSlots& joints, const BodySlots& bodies,
                              SolverBodies& sb, LaneSolver& lanes, const simd::SubstepContext& ctx,
                              Pass which, const Crew& crew) {
  // Runs work(part) for each part this thread has.
  const auto each_part = [&](auto&& work) {
    for (int p = crew.first_part; p < crew.end_part; ++p) work(island.parts[p], p);
  };
  const bool with_bias = which.with_bias;
  // Column `column` of the impulse changes dp into the part's joints' lanes.
  const auto hand_over = [&](const Part& part, const auto& dp, int column) {
    for (const std::uint32_t k : part.joints) {
      const float delta[3] = {static_cast<float>(dp[k](0, column)),
                              static_cast<float>(dp[k](1, column)),
                              static_cast<float>(dp[k](2, column))};
      lanes.add_impulses(island.joints[k], delta);
    }
  };
  if (with_bias && island.folded) {
    // The last relax pass solved this sub-step's velocity change (Pass::fold_next): its
    // impulses are all that is left, and none where that pass solved them with its own
    // (Pass::fold_apart: nobody reads them). (The lead clears the flags in the next relax pass,
    // after every thread has read them.)
    if (which.add_impulses && !island.folded_together)
      each_part([&](Part& part, int) { hand_over(part, island.dp_triple, 2); });
    return;
  }
  // A relax pass that folds the next sub-step's solve pass in solves three right sides, or
  // two where that pass's impulses are not read (Pass::fold_apart).
  const bool fold = !with_bias && which.fold_next && !island.damped && !island.contacted;
  const bool fold_apart = fold && which.fold_apart;
  // A solve pass may reuse the factor of the last sub-step's relax pass (Pass says when):
  // the bodies have moved only by the position projection since. (The lead writes the flags
  // below in the root part, after every thread has read them.)
  const bool reuse_factor = with_bias && which.reuse_relax_factor && island.relax_factored;
  const double bias_rate = with_bias ? double(ctx.rigid.bias_rate) : 0.0;
  const double bound = double(ctx.max_correction_speed);
  const double step = bound * double(ctx.h);
  // Joint k's anchors now, as the kernels see them: the step-start anchors in double, turned
  // by the rotation since.
  const auto anchors_now = [&](std::size_t k) {
    const PoseNow pa = pose_now(sb.delta[static_cast<std::size_t>(island.solver_a[k])]);
    const PoseNow pb = pose_now(sb.delta[static_cast<std::size_t>(island.solver_b[k])]);
    Anchors n{pa.dq * island.anchor_a[k], pb.dq * island.anchor_b[k], {}};
    n.separation = island.offset[k] + (pb.dp - pa.dp) + (n.r_b - n.r_a);
    return n;
  };
  // What the next sub-step's velocity integration adds to a body (island-local index `local`,
  // -1 for one that does not move; `record` its solver record) before any damping: gravity and
  // applied forces, applied torques (simd/body_integration.hpp), for a folding relax pass.
  const double h = double(ctx.h);
  const auto next_change = [&](std::int32_t local, std::int32_t record) {
    Vec6 change = Vec6::Zero();
    if (local < 0) return change;
    const simd::ForceRecord& f = sb.force[static_cast<std::size_t>(record)];
    for (int k = 0; k < 3 && which.gravity; ++k) change[k] = h * double(f.gravity[k]);
    for (int k = 0; k < 3 && which.torque; ++k)
      change[3 + k] = h * double(f.angular_acceleration[k]);
    return change;
  };
  // The rows, the part's share of the factor, and its half of the solve up to the root.
  each_part([&](Part& part, int p) {
    // W = M^-1 per body from the solver's mass record (the geometric-stiffness inertia
    // included), so the exact pass and the Gauss-Seidel passes solve with the same masses.
    // Read by a solve pass that factors or starts a step (the geometric inertia is new there:
    // a reused factor's velocity changes take the new masses, and so does the relax pass's
    // factor after it): a relax pass runs after its sub-step's solve pass, with no mass record
    // changed between (an inertia refresh comes before a sub-step's velocities; where one does,
    // that solve pass factors), and a folded solve pass follows a relax pass with none before
    // it either (step.cpp).
    const bool read_masses = with_bias && (!reuse_factor || which.step_start);
    for (std::size_t i = 0; i < part.bodies.size() && read_masses; ++i) {
      const std::uint32_t b = part.bodies[i];
      const simd::MassRecord& m = sb.mass[island.bodies[b] + 1];
      InverseMass& w = island.inverse_mass[b];
      w.linear = double(m.inv_mass);
      w.angular << m.inv_inertia[0], m.inv_inertia[3], m.inv_inertia[4], m.inv_inertia[3],
          m.inv_inertia[1], m.inv_inertia[5], m.inv_inertia[4], m.inv_inertia[5], m.inv_inertia[2];
    }
    for (const std::uint32_t k : part.joints) {
      const std::int32_t ia = island.solver_a[k], ib = island.solver_b[k];
      TreeJoint& t = island.rows[k];
      const double rest_length = island.rest_length[k];
      if (which.step_start) {
        const JointSlot& slot = joints[island.joints[k]];
        const BodySlot& a = bodies[slot.body_a];
        const BodySlot& b = bodies[slot.body_b];
        island.anchor_a[k] = a.orientation * slot.local_anchor_a;
        island.anchor_b[k] = b.orientation * slot.local_anchor_b;
        island.offset[k] = b.position - a.position;
        island.held_back[k] = violation_size(
            t, rest_length, island.offset[k] + island.anchor_b[k] - island.anchor_a[k]);
      }
      // At a step's start the bodies are where the step-start anchors were turned (their
      // deltas the identity): the anchors as they are, the same bits as turned again.
      const auto [r_a, r_b, separation] =
          which.step_start ? Anchors{island.anchor_a[k], island.anchor_b[k],
                                     island.offset[k] + (island.anchor_b[k] - island.anchor_a[k])}
                           : anchors_now(k);
      const Vec6 va = velocity_of(sb.velocity[static_cast<std::size_t>(ia)]);
      const Vec6 vb = velocity_of(sb.velocity[static_cast<std::size_t>(ib)]);
      const bool blocks = island.system.reads_blocks(k);
      Eigen::Vector3d c = violation(t, rest_length, separation);
      FourDoubles jv;
      if (reuse_factor) {
        // A reused factor keeps its Jacobians (the relax pass's) for its solve; C is today's,
        // and at a step's start J v too (Pass::reuse_relax_factor says why).
        if (which.step_start) {
          jv = jacobians_times(t.ball, r_a, r_b, separation, va, vb);
        } else if (t.ball) {  // its blocks may not be written (TreeSystem::reads_blocks)
          // r_a = a_0 and r_b = -a_1 (TreeJoint::arm), exactly
          jv = ball_times(load4(t.arm[0]), -load4(t.arm[1]), va, vb);
        } else {
          jv = times_vector(t.jacobian[0], va) + times_vector(t.jacobian[1], vb);
        }
      } else if (fold) {
        const Vec6 a[2] = {va, next_change(t.body[0], ia)}, b[2] = {vb, next_change(t.body[1], ib)};
        FourDoubles products[2];
        fill_jacobians_times(r_a, r_b, separation, a, b, t, products, blocks);
        if (fold_apart) {
          jv = products[0];
          store3(island.next_change[k].data(), products[1]);
        } else {
          jv = products[0] + products[1];
        }
      } else {
        const Vec6 a[1] = {va}, b[1] = {vb};
        FourDoubles products[1];
        fill_jacobians_times(r_a, r_b, separation, a, b, t, products, blocks);
        jv = products[0];
      }
      if (!with_bias) {
        // What the projection removes: all the violation this step's own motion made (the
        // drift of links turning fast, which the velocity solve cannot see), and of what was
        // there at the step's start (a joint created apart, a body moved by the user) at most
        // max_correction_speed * h per sub-step. Bounding the whole of C, as the biased pass
        // bounds its speed, left the 1,000-link whip's joints open 2.1 cm as it cracked (4
        // sub-steps; 2.6e-4 m bounding only what was there before).
        // Sizes, not rows: a violation held back turns with the bodies, and compared row by
        // row its turned part would pass for new.
        double& held = island.held_back[k];
        if (held > 0.0) {
          const double size = violation_size(t, rest_length, separation);
          held = std::min(held, size);  // the motion since may have closed some of it
          const double allowed = size - held + step;
          island.error[k] = size > allowed ? Eigen::Vector3d(c * (allowed / size)) : c;
          island.kept[k] = c - island.error[k];
          held = std::max(held - step, 0.0);
        } else {
          // Nothing held back (a joint whose step-start violation was under the bound, from
          // the step's second sub-step on): all of C goes, as the branch above gives for held
          // = 0, without its square root per joint (7 % of the exact pass's own samples on
          // 100 chains of 1,000 links).
          island.error[k] = c;
          island.kept[k].setZero();
        }
      }
      const Eigen::Vector3d bias = (bias_rate * c).cwiseMax(-bound).cwiseMin(bound);
      store3(t.residual.data(), jv + load3(bias.data()));
    }
    if (reuse_factor) {
      island.system.solve_up<1>(p, island.rows, {});
    } else if (with_bias) {
      island.system.factor_solve_up<1>(p, island.inverse_mass, island.rows, {});
    } else if (fold_apart) {
      island.system.factor_solve_up<3>(p, island.inverse_mass, island.rows,
                                       {&island.error, &island.next_change});
    } else {
      island.system.factor_solve_up<2>(p, island.inverse_mass, island.rows, {&island.error});
    }
  });
  crew.sync();
  if (crew.lead) {
    island.relax_factored = !with_bias;
    if (!with_bias) {
      island.folded = fold;
      island.folded_together = fold && !fold_apart;
    }
    if (reuse_factor) {
      island.system.solve_root<1>(island.rows, island.dv, island.dp);
    } else if (with_bias) {
      island.system.factor_solve_root<1>(island.inverse_mass, island.rows, island.dv, island.dp);
    } else if (fold_apart) {
      island.system.factor_solve_root<3>(island.inverse_mass, island.rows, island.dv_triple,
                                         island.dp_triple);
    } else {
      island.system.factor_solve_root<2>(island.inverse_mass, island.rows, island.dv_pair,
                                         island.dp_pair);
    }
  }
  crew.sync();
  // The velocity changes (column 0 of dv; a folding relax pass's column 2 too) into the part's
  // bodies' velocities and the impulse changes (column 0 of dp) into its joints' lanes, read
  // where the solve left them.
  const auto apply = [&](const Part& part, const auto& dv, const auto& dp) {
    for (const std::uint32_t b : part.bodies) {
      simd::VelocityRecord& v = sb.velocity[island.bodies[b] + 1];
      Vec6 now = velocity_of(v) + dv[b].col(0);
      if constexpr (std::decay_t<decltype(dv[b])>::ColsAtCompileTime == 3) now += dv[b].col(2);
      for (int k = 0; k < 3; ++k) {
        v.v[k] = static_cast<float>(now[k]);
        v.w[k] = static_cast<float>(now[3 + k]);
      }
    }
    if (which.add_impulses) hand_over(part, dp, 0);
  };
  if (with_bias) {
    each_part([&](Part& part, int p) {
      island.system.solve_down<1>(p, island.rows, island.dv, island.dp);
      apply(part, island.dv, island.dp);
    });
    return;
  }
  // The velocities and the position projection together (move_positions, below).
  const auto relax_down = [&](auto& dv, auto& dp) {
    constexpr int kColumns = std::decay_t<decltype(dv[0])>::ColsAtCompileTime;
    each_part([&](Part& part, int p) {
      island.system.solve_down<kColumns>(p, island.rows, dv, dp);
      apply(part, dv, dp);
      move_positions(part.bodies, island.bodies, sb, [&](std::size_t b) { return dv[b].col(1); });
    });
  };
  if (fold_apart) {
    relax_down(island.dv_triple, island.dp_triple);
  } else {
    relax_down(island.dv_pair, island.dp_pair);
  }
  // Where the projection left a joint open by more than kProjectionTolerance (besides what is
  // held back), Newton steps: the rows again at the projected positions, a new factor, and
  // J dx = -C once more. The whips need them where links turn
  // fast: the 100-link whip cracking at 4 sub-steps (160 rad/s) kept 7 mm after one
  // projection, 0.8 mm after two more with the same factor, 1e-6 m after two Newton steps.
  // Only where the pass asks (a step's last sub-step): before, the next sub-step's projection
  // takes out whatever this one left, with the drift of its own motion.
  for (int extra = 0; extra < kMaxExtraProjections && which.check; ++extra) {
    crew.sync();  // a joint between the parts reads both bodies' new positions
    each_part([&](Part& part, int p) {
      double worst = 0.0;
      for (const std::uint32_t k : part.joints) {
        island.anchors[k] = anchors_now(k);
        const Eigen::Vector3d left =
            violation(island.rows[k], island.rest_length[k], island.anchors[k].separation) -
            island.kept[k];
        island.rows[k].residual = left;
        worst = std::max(worst, left.cwiseAbs().maxCoeff());
      }
      island.worst[p] = worst;
    });
    crew.sync();
    if (std::max(island.worst[0], island.worst[1]) <= kProjectionTolerance) return;
    each_part([&](Part& part, int p) {
      for (const std::uint32_t k : part.joints) {
        const Anchors& now = island.anchors[k];
        fill_jacobians(now.r_a, now.r_b, now.separation, island.rows[k]);
      }
      island.system.factor_solve_up<1>(p, island.inverse_mass, island.rows, {});
    });
    crew.sync();
    if (crew.lead) {
      island.system.factor_solve_root<1>(island.inverse_mass, island.rows, island.dv, island.dp);
    }
    crew.sync();
    each_part([&](Part& part, int p) {
      island.system.solve_down<1>(p, island.rows, island.dv, island.dp);
      move_positions(part.bodies, island.bodies, sb, [&](std::size_t b) { return island.dv[b]; });
    });
  }
}

}  // namespace softstep::solver
