// The joints of one lane width: packing from the colouring, the per-step anchor pass, and
// the stage loops (each colour's groups, then the overflow set in order).
#include <algorithm>
#include <limits>
#include <stdexcept>

#include "solver/joint_batches.hpp"
#include "solver/team.hpp"
#include "world_impl.hpp"

namespace softstep {
namespace {

using solver::ColorBatches;
using solver::JointFeatures;
using solver::KernelTable;
using solver::RowKind;
using solver::Run;

// Where a joint's lane is, for reading its impulse.
struct LaneRef {
  bool overflow = false;
  std::uint32_t color = 0;  // index into colors_ (non-empty colours only)
  std::uint32_t group = 0;
  std::uint32_t lane = 0;
};

template <int W, class Group>
void fill_common_lane(Group& g, int lane, std::uint32_t slot, const JointSlot& j,
                      const std::vector<BodySlot>& bodies) {
  g.id[lane] = slot;
  g.body_a[lane] = solver_index(bodies[j.body_a], j.body_a);
  g.body_b[lane] = solver_index(bodies[j.body_b], j.body_b);
  g.hertz[lane] = static_cast<float>(j.spring.hertz);
  g.zeta[lane] = static_cast<float>(j.spring.damping_ratio);
}

// A padding lane: both bodies the static dummy, no spring, no limits: it applies nothing.
template <class Group>
Group empty_group() {
  Group g{};
  std::fill(std::begin(g.id), std::end(g.id), simd::kPaddingLane);
  return g;
}

template <int W>
void fill_lane(simd::BallJointGroup<W>& g, int lane, std::uint32_t slot, const JointSlot& j,
               const std::vector<BodySlot>& bodies) {
  fill_common_lane<W>(g, lane, slot, j, bodies);
  for (int k = 0; k < 3; ++k) g.impulse[k][lane] = j.impulse[k];
}

template <int W>
void fill_lane(simd::DistanceJointGroup<W>& g, int lane, std::uint32_t slot, const JointSlot& j,
               const std::vector<BodySlot>& bodies) {
  fill_common_lane<W>(g, lane, slot, j, bodies);
  const bool rigid = j.spring.is_rigid();
  g.rest_length[lane] = static_cast<float>(j.rest_length);
  g.min_length[lane] = static_cast<float>(j.min_length);
  g.max_length[lane] = static_cast<float>(j.max_length);
  g.lower_enabled[lane] = (!rigid && j.min_length > 0.0) ? 1.0f : 0.0f;
  g.upper_enabled[lane] =
      (!rigid && j.max_length < std::numeric_limits<double>::infinity()) ? 1.0f : 0.0f;
  g.impulse[lane] = j.impulse.x();
  g.lower_impulse[lane] = j.impulse.y();
  g.upper_impulse[lane] = j.impulse.z();
}

// The kernel variant a joint runs with (see joint_batches.hpp); 0, the general kernel, when
// the world does not specialize.
std::uint8_t variant_of(const JointSlot& j, bool specialize) {
  if (!specialize) return 0;
  const RowKind row = j.spring.is_rigid()  ? RowKind::Rigid
                      : j.spring.is_free() ? RowKind::Free
                                           : RowKind::Soft;
  JointFeatures f{row, false, false};
  if (j.type == JointType::Distance && row != RowKind::Rigid) {
    f.lower = j.min_length > 0.0;
    f.upper = j.max_length < std::numeric_limits<double>::infinity();
  }
  const auto find = [&](const auto& variants) {
    for (std::size_t i = 1; i < variants.size(); ++i) {
      if (variants[i] == f) return static_cast<std::uint8_t>(i);
    }
    throw std::logic_error("variant_of: no kernel variant for this joint");
  };
  return j.type == JointType::Ball ? find(solver::kBallVariants) : find(solver::kDistanceVariants);
}

template <int W>
Eigen::Vector3f lane_impulse(const simd::BallJointGroup<W>& g, std::uint32_t lane) {
  return {g.impulse[0][lane], g.impulse[1][lane], g.impulse[2][lane]};
}
template <int W>
Eigen::Vector3f lane_impulse(const simd::DistanceJointGroup<W>& g, std::uint32_t lane) {
  return {g.impulse[lane], g.lower_impulse[lane], g.upper_impulse[lane]};
}

// World-frame anchors and centre offset at the step start, from the double-precision poses:
// far from the origin a float position has mm-sized steps, a float difference does not.
template <class Group>
void write_anchors(Group& g, int lane, const JointSlot& j, const std::vector<BodySlot>& bodies) {
  const BodySlot& a = bodies[j.body_a];
  const BodySlot& b = bodies[j.body_b];
  const Eigen::Vector3d r_a = a.orientation * j.local_anchor_a;
  const Eigen::Vector3d r_b = b.orientation * j.local_anchor_b;
  const Eigen::Vector3d center_delta = b.position - a.position;
  for (int k = 0; k < 3; ++k) {
    g.r_a[k][lane] = static_cast<float>(r_a[k]);
    g.r_b[k][lane] = static_cast<float>(r_b[k]);
    g.center_delta[k][lane] = static_cast<float>(center_delta[k]);
  }
}

template <class Group>
void zero_impulses(Group& g) {
  if constexpr (requires { g.lower_impulse; }) {
    std::fill(std::begin(g.impulse), std::end(g.impulse), 0.0f);
    std::fill(std::begin(g.lower_impulse), std::end(g.lower_impulse), 0.0f);
    std::fill(std::begin(g.upper_impulse), std::end(g.upper_impulse), 0.0f);
  } else {
    for (auto& row : g.impulse) std::fill(std::begin(row), std::end(row), 0.0f);
  }
}

// Rows one lane of a variant solves per pass: 3 for a ball joint, the spring row (unless
// free) and the limit rows for a distance joint (the general kernel evaluates all three).
int rows_of(JointType type, JointFeatures f) {
  if (type == JointType::Ball) return f.row == RowKind::Free ? 0 : 3;
  if (f.row == RowKind::Any) return 3;
  return (f.row == RowKind::Free ? 0 : 1) + (f.lower ? 1 : 0) + (f.upper ? 1 : 0);
}

template <int W>
class LaneSolverImpl final : public LaneSolver {
 public:
  explicit LaneSolverImpl(KernelTable<W> kernels)
      : kernels_(kernels), scalar_(solver::scalar_kernels()) {}

  int lanes() const override { return W; }

  void pack(const graph_coloring::GraphColoring& coloring, const std::vector<JointSlot>& joints,
            const std::vector<BodySlot>& bodies, bool specialize) override {
    colors_.clear();
    overflow_ = {};
    lane_of_.assign(joints.size(), LaneRef{});
    lane_known_.assign(joints.size(), false);
    lane_is_ball_.assign(joints.size(), false);
    for (int c = 0; c < graph_coloring::kColorCount; ++c) {
      const auto members = coloring.members(c);
      if (members.empty()) continue;
      ColorBatches<W> batches;
      const auto color = static_cast<std::uint32_t>(colors_.size());
      add_members<W>(batches, members, joints, bodies, specialize, false, color);
      if (!batches.ball.empty() || !batches.distance.empty()) colors_.push_back(std::move(batches));
    }
    add_members<1>(overflow_, coloring.overflow(), joints, bodies, specialize, true, 0);
    count_uses();
  }

  void save_impulses(std::vector<JointSlot>& joints) const override {
    for (std::uint32_t j = 0; j < joints.size(); ++j) {
      if (joints[j].alive && in_lanes(j)) joints[j].impulse = impulse(j);
    }
  }

  bool in_lanes(std::uint32_t joint_slot) const override {
    return joint_slot < lane_known_.size() && lane_known_[joint_slot];
  }

  Eigen::Vector3f impulse(std::uint32_t joint_slot) const override {
    const LaneRef& r = lane_of_[joint_slot];
    const bool ball = lane_is_ball_[joint_slot];
    if (r.overflow) {
      return ball ? lane_impulse(overflow_.ball[r.group], r.lane)
                  : lane_impulse(overflow_.distance[r.group], r.lane);
    }
    const ColorBatches<W>& c = colors_[r.color];
    return ball ? lane_impulse(c.ball[r.group], r.lane) : lane_impulse(c.distance[r.group], r.lane);
  }

  void accumulate_geometric_inertia(const std::vector<JointSlot>& joints, double factor,
                                    std::vector<double>& extra) const override {
    for_each_lane([&](const auto& group, int lane, std::uint32_t slot) {
      const Eigen::Vector3f p = lane_impulse(group, static_cast<std::uint32_t>(lane));
      constexpr bool ball = requires {
        group.impulse[0][0];
      };
      const double magnitude = ball ? double(p.norm()) : std::abs(double(p.x() + p.y() - p.z()));
      if (magnitude == 0.0) return;
      const JointSlot& j = joints[slot];
      extra[j.body_a] += factor * magnitude * j.local_anchor_a.norm();
      extra[j.body_b] += factor * magnitude * j.local_anchor_b.norm();
    });
  }

  const std::vector<KernelUse>& uses() const override { return uses_; }
  bool needs(Pass pass) const override { return needs_[static_cast<int>(pass)]; }

  void prepare(const std::vector<JointSlot>& joints, const std::vector<BodySlot>& bodies,
               const simd::SubstepContext& ctx, const solver::Share& share) override {
    visit_lanes(*this, share, [&](auto& group, int lane, std::uint32_t joint) {
      write_anchors(group, lane, joints[joint], bodies);
    });
    for (auto& c : colors_) run_share(c, kernels_, share, &Ball::prepare, &Distance::prepare, ctx);
    if (share.thread == 0) {
      run_share(overflow_, scalar_, solver::Share{}, &Ball1::prepare, &Distance1::prepare, ctx);
    }
  }

  void warm_start(const simd::BodyArrays& arrays, const solver::Share& share) override {
    run_colors(share, &Ball::warm_start, &Distance::warm_start, &Ball1::warm_start,
               &Distance1::warm_start, arrays);
  }

  void clear_impulses(const solver::Share& share) override {
    visit_groups(share, [](auto& g) { zero_impulses(g); });
  }

  void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const solver::Share& share) override {
    run_colors(share, &Ball::solve, &Distance::solve, &Ball1::solve, &Distance1::solve, arrays,
               ctx);
  }

  void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const solver::Share& share) override {
    run_colors(share, &Ball::relax, &Distance::relax, &Ball1::relax, &Distance1::relax, arrays,
               ctx);
  }

  void integrate_velocities(SolverBodies& b, const simd::SubstepContext& ctx, bool gravity,
                            bool damping, bool torque, const solver::Share& share) override {
    const solver::Slice mine = solver::slice_of(b.blocks.size(), share);
    kernels_.integrate_velocities[gravity][damping][torque](b.velocity.data(), b.force.data(),
                                                            b.blocks.data() + mine.begin,
                                                            mine.end - mine.begin, ctx);
  }

  void integrate_positions(SolverBodies& b, float h, const solver::Share& share) override {
    const solver::Slice mine = solver::slice_of(b.blocks.size(), share);
    kernels_.integrate_positions(b.delta.data(), b.velocity.data(), b.blocks.data() + mine.begin,
                                 mine.end - mine.begin, h);
  }

 private:
  using Ball = solver::VariantKernels<simd::BallJointGroup<W>>;
  using Distance = solver::VariantKernels<simd::DistanceJointGroup<W>>;
  using Ball1 = solver::VariantKernels<simd::BallJointGroup<1>>;
  using Distance1 = solver::VariantKernels<simd::DistanceJointGroup<1>>;

  // This thread's share of every run of one colour (or of the overflow set) through the
  // pass `ball_pass` / `distance_pass` of the run's variant; a variant without the pass is
  // skipped.
  template <int V, class BallPass, class DistancePass, class... Args>
  static void run_share(ColorBatches<V>& c, const KernelTable<V>& table, const solver::Share& share,
                        BallPass ball_pass, DistancePass distance_pass, const Args&... args) {
    const auto run = [&](auto& groups, const std::vector<Run>& runs, const auto& kernels,
                         auto pass) {
      for (const Run& r : runs) {
        const auto fn = kernels[r.variant].*pass;
        if (fn == nullptr) continue;
        const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
        if (slice.end > slice.begin)
          fn(groups.data() + r.begin + slice.begin, slice.end - slice.begin, args...);
      }
    };
    run(c.ball, c.ball_runs, table.ball, ball_pass);
    run(c.distance, c.distance_runs, table.distance, distance_pass);
  }

  // Colour by colour, each thread its share, a barrier after each colour (joints of the next
  // colour read bodies this one wrote); then the overflow set on thread 0, in order.
  template <class BallPass, class DistancePass, class Ball1Pass, class Distance1Pass, class... Args>
  void run_colors(const solver::Share& share, BallPass ball_pass, DistancePass distance_pass,
                  Ball1Pass ball1_pass, Distance1Pass distance1_pass, const Args&... args) {
    for (auto& c : colors_) {
      run_share(c, kernels_, share, ball_pass, distance_pass, args...);
      team_barrier(share);
    }
    if (!overflow_.ball.empty() || !overflow_.distance.empty()) {
      if (share.thread == 0) {
        run_share(overflow_, scalar_, solver::Share{}, ball1_pass, distance1_pass, args...);
      }
      team_barrier(share);
    }
  }

  template <class F>
  void visit_groups(const solver::Share& share, F&& f) {
    for (auto& c : colors_) {
      const solver::Slice b = solver::slice_of(c.ball.size(), share);
      for (std::size_t i = b.begin; i < b.end; ++i) f(c.ball[i]);
      const solver::Slice d = solver::slice_of(c.distance.size(), share);
      for (std::size_t i = d.begin; i < d.end; ++i) f(c.distance[i]);
    }
    if (share.thread == 0) {
      for (auto& g : overflow_.ball) f(g);
      for (auto& g : overflow_.distance) f(g);
    }
  }

  // A joint is in the lanes unless its bodies sleep (both movable ends of a joint share an
  // island, so one end asleep means the joint is).
  static bool asleep(const JointSlot& j, const std::vector<BodySlot>& bodies) {
    return bodies[j.body_a].asleep || bodies[j.body_b].asleep;
  }

  // Lays out one colour's members (or the overflow set): per type, one run per variant in
  // variant order, each packed into groups of V lanes. Members keep their order within a
  // variant, so the overflow set's sequential order is the same at every width.
  template <int V>
  void add_members(ColorBatches<V>& batches, std::span<const std::uint32_t> members,
                   const std::vector<JointSlot>& joints, const std::vector<BodySlot>& bodies,
                   bool specialize, bool overflow, std::uint32_t color) {
    std::array<std::vector<std::uint32_t>, solver::kBallVariants.size()> ball;
    std::array<std::vector<std::uint32_t>, solver::kDistanceVariants.size()> distance;
    for (std::uint32_t j : members) {
      if (asleep(joints[j], bodies)) continue;
      const std::uint8_t v = variant_of(joints[j], specialize);
      (joints[j].type == JointType::Ball ? ball[v] : distance[v]).push_back(j);
    }
    const auto place = [&](auto& groups, std::vector<Run>& runs, const auto& lists, bool is_ball) {
      using Group = typename std::decay_t<decltype(groups)>::value_type;
      for (std::size_t v = 0; v < lists.size(); ++v) {
        if (lists[v].empty()) continue;
        const auto lanes = graph_coloring::pack_lanes(lists[v], V, kPadding);
        const auto begin = static_cast<std::uint32_t>(groups.size());
        groups.resize(begin + lanes.size() / V, empty_group<Group>());
        for (std::size_t i = 0; i < lanes.size(); ++i) {
          const std::uint32_t j = lanes[i];
          const auto group = static_cast<std::uint32_t>(begin + i / V);
          const auto lane = static_cast<std::uint32_t>(i % V);
          if (j == kPadding) continue;
          fill_lane<V>(groups[group], static_cast<int>(lane), j, joints[j], bodies);
          lane_of_[j] = {overflow, color, group, lane};
          lane_known_[j] = true;
          lane_is_ball_[j] = is_ball;
        }
        runs.push_back(
            {static_cast<std::uint8_t>(v), begin, static_cast<std::uint32_t>(groups.size())});
      }
    };
    place(batches.ball, batches.ball_runs, ball, true);
    place(batches.distance, batches.distance_runs, distance, false);
  }

  // Per variant in use: groups and joints (for the plan), and which passes anything needs.
  void count_uses() {
    uses_.clear();
    needs_.fill(false);
    const auto count = [&](JointType type, const auto& variants, const auto& groups,
                           const std::vector<Run>& runs, int width) {
      for (const Run& r : runs) {
        const JointFeatures f = variants[r.variant];
        auto it = std::find_if(uses_.begin(), uses_.end(), [&](const KernelUse& u) {
          return u.type == type && u.variant == r.variant;
        });
        if (it == uses_.end()) {
          it = uses_.insert(std::upper_bound(uses_.begin(), uses_.end(), KernelUse{type, r.variant},
                                             [](const KernelUse& x, const KernelUse& y) {
                                               return std::pair(x.type, x.variant) <
                                                      std::pair(y.type, y.variant);
                                             }),
                            KernelUse{type, r.variant});
          it->features = f;
          it->rows_per_joint = rows_of(type, f);
        }
        it->batches += r.end - r.begin;
        for (std::uint32_t g = r.begin; g < r.end; ++g) {
          for (int lane = 0; lane < width; ++lane) it->joints += groups[g].id[lane] != kPadding;
        }
        const bool ball = type == JointType::Ball;
        needs_[static_cast<int>(Pass::Solve)] |=
            ball ? simd::ball_needs_solve(f) : simd::distance_needs_solve(f);
        needs_[static_cast<int>(Pass::Relax)] |=
            ball ? simd::ball_needs_relax(f) : simd::distance_needs_relax(f);
      }
    };
    for (const auto& c : colors_) {
      count(JointType::Ball, solver::kBallVariants, c.ball, c.ball_runs, W);
      count(JointType::Distance, solver::kDistanceVariants, c.distance, c.distance_runs, W);
    }
    count(JointType::Ball, solver::kBallVariants, overflow_.ball, overflow_.ball_runs, 1);
    count(JointType::Distance, solver::kDistanceVariants, overflow_.distance,
          overflow_.distance_runs, 1);
  }

  // Visits every real lane of this thread's share of the groups of every colour, then (on
  // thread 0 only) of the overflow set. Self is LaneSolverImpl or const LaneSolverImpl.
  template <class Self, class F>
  static void visit_lanes(Self& self, const solver::Share& share, F&& f) {
    const auto visit = [&](auto& groups, int width, const solver::Share& part) {
      const solver::Slice slice = solver::slice_of(groups.size(), part);
      for (std::size_t i = slice.begin; i < slice.end; ++i) {
        auto& g = groups[i];
        for (int lane = 0; lane < width; ++lane) {
          if (g.id[lane] != kPadding) f(g, lane, g.id[lane]);
        }
      }
    };
    for (auto& c : self.colors_) {
      visit(c.ball, W, share);
      visit(c.distance, W, share);
    }
    if (share.thread == 0) {
      visit(self.overflow_.ball, 1, solver::Share{});
      visit(self.overflow_.distance, 1, solver::Share{});
    }
  }
  template <class F>
  void for_each_lane(F&& f) const {
    visit_lanes(*this, solver::Share{}, f);
  }

  static constexpr std::uint32_t kPadding = simd::kPaddingLane;
  KernelTable<W> kernels_;
  KernelTable<1> scalar_;
  std::vector<ColorBatches<W>> colors_;
  ColorBatches<1> overflow_;
  std::vector<LaneRef> lane_of_;
  std::vector<bool> lane_known_;
  std::vector<bool> lane_is_ball_;
  std::vector<KernelUse> uses_;
  std::array<bool, 2> needs_{};
};

}  // namespace

bool simd_width_supported(SimdWidth width) {
  __builtin_cpu_init();
  const bool fma_ok = !SOFTSTEP_USE_FMA || __builtin_cpu_supports("fma");
  switch (width) {
    case SimdWidth::Best:
    case SimdWidth::Scalar:
      return true;
    case SimdWidth::Sse:
      return __builtin_cpu_supports("sse4.2") && fma_ok;
    case SimdWidth::Avx2:
      return __builtin_cpu_supports("avx2") && fma_ok;
  }
  return false;
}

SimdWidth best_simd_width() {
  if (simd_width_supported(SimdWidth::Avx2)) return SimdWidth::Avx2;
  if (simd_width_supported(SimdWidth::Sse)) return SimdWidth::Sse;
  return SimdWidth::Scalar;
}

const char* simd_width_name(SimdWidth width) {
  switch (width) {
    case SimdWidth::Best:
      return "best";
    case SimdWidth::Scalar:
      return "scalar";
    case SimdWidth::Sse:
      return "sse";
    case SimdWidth::Avx2:
      return "avx2";
  }
  return "?";
}

std::unique_ptr<LaneSolver> make_lane_solver(SimdWidth width) {
  switch (width) {
    case SimdWidth::Scalar:
      return std::make_unique<LaneSolverImpl<1>>(solver::scalar_kernels());
    case SimdWidth::Sse:
      return std::make_unique<LaneSolverImpl<4>>(solver::sse_kernels());
    case SimdWidth::Avx2:
      return std::make_unique<LaneSolverImpl<8>>(solver::avx2_kernels());
    case SimdWidth::Best:
      break;
  }
  throw std::logic_error("make_lane_solver: width must be resolved");
}

}  // namespace softstep
