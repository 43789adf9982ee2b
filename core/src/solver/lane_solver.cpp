// The joints of one lane width: packing from the colouring, the per-step anchor pass, and
// the stage loops (each colour's groups, then the overflow set in order).
#include <stdexcept>

#include "solver/joint_batches.hpp"
#include "world_impl.hpp"

namespace softstep {
namespace {

using solver::ColorBatches;
using solver::KernelTable;

// Where a joint's lane is, for reading its impulse.
struct LaneRef {
  bool overflow = false;
  std::uint32_t color = 0;  // index into colors_ (non-empty colours only)
  std::uint32_t group = 0;
  std::uint32_t lane = 0;
};

template <int W, class Group>
void fill_common_lane(Group& g, int lane, const JointSlot& j, const std::vector<BodySlot>& bodies) {
  g.body_a[lane] = solver_index(bodies[j.body_a], j.body_a);
  g.body_b[lane] = solver_index(bodies[j.body_b], j.body_b);
  g.hertz[lane] = static_cast<float>(j.spring.hertz);
  g.zeta[lane] = static_cast<float>(j.spring.damping_ratio);
}

// A padding lane: both bodies the static dummy, no spring, no limits: it applies nothing.
template <class Group>
Group empty_group() {
  Group g{};
  return g;
}

template <int W>
void fill_lane(simd::BallJointGroup<W>& g, int lane, const JointSlot& j,
               const std::vector<BodySlot>& bodies) {
  fill_common_lane<W>(g, lane, j, bodies);
  for (int k = 0; k < 3; ++k) g.impulse[k][lane] = j.impulse[k];
}

template <int W>
void fill_lane(simd::DistanceJointGroup<W>& g, int lane, const JointSlot& j,
               const std::vector<BodySlot>& bodies) {
  fill_common_lane<W>(g, lane, j, bodies);
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

template <int W>
class LaneSolverImpl final : public LaneSolver {
 public:
  explicit LaneSolverImpl(KernelTable<W> kernels)
      : kernels_(kernels), scalar_(solver::scalar_kernels()) {}

  int lanes() const override { return W; }

  void pack(const graph_coloring::GraphColoring& coloring, const std::vector<JointSlot>& joints,
            const std::vector<BodySlot>& bodies) override {
    colors_.clear();
    overflow_ = {};
    lane_of_.assign(joints.size(), LaneRef{});
    lane_known_.assign(joints.size(), false);
    lane_is_ball_.assign(joints.size(), false);
    lane_joint_.clear();
    for (int c = 0; c < graph_coloring::kColorCount; ++c) {
      const auto members = coloring.members(c);
      if (members.empty()) continue;
      ColorBatches<W>& batches = colors_.emplace_back();
      const auto color = static_cast<std::uint32_t>(colors_.size() - 1);
      add_members<W>(batches, members, joints, bodies, false, color);
    }
    add_members<1>(overflow_, coloring.overflow(), joints, bodies, true, 0);
  }

  void save_impulses(std::vector<JointSlot>& joints) const override {
    for (std::uint32_t j = 0; j < joints.size(); ++j) {
      if (joints[j].alive && j < lane_of_.size() && lane_known_[j]) joints[j].impulse = impulse(j);
    }
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
      constexpr bool ball = requires { group.impulse[0][0]; };
      const double magnitude = ball ? double(p.norm()) : std::abs(double(p.x() + p.y() - p.z()));
      if (magnitude == 0.0) return;
      const JointSlot& j = joints[slot];
      extra[j.body_a] += factor * magnitude * j.local_anchor_a.norm();
      extra[j.body_b] += factor * magnitude * j.local_anchor_b.norm();
    });
  }

  void prepare(const std::vector<JointSlot>& joints, const std::vector<BodySlot>& bodies,
               const simd::SubstepContext& ctx) override {
    for_each_lane([&](auto& group, int lane, std::uint32_t joint) {
      write_anchors(group, lane, joints[joint], bodies);
    });
    for (auto& c : colors_) kernels_.prepare(c, ctx);
    scalar_.prepare(overflow_, ctx);
  }

  void warm_start(const simd::BodyArrays& arrays) override {
    for (auto& c : colors_) kernels_.warm_start(c, arrays);
    scalar_.warm_start(overflow_, arrays);
  }

  void clear_impulses() override {
    for (auto& c : colors_) {
      for (auto& g : c.ball) zero_impulses(g);
      for (auto& g : c.distance) zero_impulses(g);
    }
    for (auto& g : overflow_.ball) zero_impulses(g);
    for (auto& g : overflow_.distance) zero_impulses(g);
  }

  void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx) override {
    for (auto& c : colors_) kernels_.solve(c, arrays, ctx);
    scalar_.solve(overflow_, arrays, ctx);
  }

  void integrate_velocities(SolverBodies& b, float h) override {
    kernels_.integrate_velocities(b.velocity.data(), b.force.data(), b.padded_count(), h);
  }

  void integrate_positions(SolverBodies& b, float h) override {
    kernels_.integrate_positions(b.delta.data(), b.velocity.data(), b.padded_count(), h);
  }

  void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx) override {
    for (auto& c : colors_) kernels_.relax(c, arrays, ctx);
    scalar_.relax(overflow_, arrays, ctx);
  }

 private:
  template <int V>
  void add_members(ColorBatches<V>& batches, std::span<const std::uint32_t> members,
                   const std::vector<JointSlot>& joints, const std::vector<BodySlot>& bodies,
                   bool overflow, std::uint32_t color) {
    std::vector<std::uint32_t> ball, distance;
    for (std::uint32_t j : members)
      (joints[j].type == JointType::Ball ? ball : distance).push_back(j);
    const auto place = [&](auto& groups, const std::vector<std::uint32_t>& list, bool is_ball) {
      using Group = typename std::decay_t<decltype(groups)>::value_type;
      const auto lanes = graph_coloring::pack_lanes(list, V, kPadding);
      groups.assign(lanes.size() / V, empty_group<Group>());
      for (std::size_t i = 0; i < lanes.size(); ++i) {
        const std::uint32_t j = lanes[i];
        const auto group = static_cast<std::uint32_t>(i / V);
        const auto lane = static_cast<std::uint32_t>(i % V);
        lane_joint_.push_back(j);
        if (j == kPadding) continue;
        fill_lane<V>(groups[group], static_cast<int>(lane), joints[j], bodies);
        lane_of_[j] = {overflow, color, group, lane};
        lane_known_[j] = true;
        lane_is_ball_[j] = is_ball;
      }
    };
    place(batches.ball, ball, true);
    place(batches.distance, distance, false);
  }

  // Visits every real lane (ball groups, then distance groups; colours, then overflow) in
  // the order add_members recorded them in lane_joint_.
  // Self is LaneSolverImpl or const LaneSolverImpl: one visitor for reading and writing.
  template <class Self, class F>
  static void visit_lanes(Self& self, F&& f) {
    std::size_t k = 0;
    const auto visit = [&](auto& groups, int width) {
      for (auto& g : groups) {
        for (int lane = 0; lane < width; ++lane, ++k) {
          if (self.lane_joint_[k] != kPadding) f(g, lane, self.lane_joint_[k]);
        }
      }
    };
    for (auto& c : self.colors_) {
      visit(c.ball, W);
      visit(c.distance, W);
    }
    visit(self.overflow_.ball, 1);
    visit(self.overflow_.distance, 1);
  }
  template <class F>
  void for_each_lane(F&& f) {
    visit_lanes(*this, f);
  }
  template <class F>
  void for_each_lane(F&& f) const {
    visit_lanes(*this, f);
  }

  static constexpr std::uint32_t kPadding = 0xFFFFFFFFu;
  KernelTable<W> kernels_;
  KernelTable<1> scalar_;
  std::vector<ColorBatches<W>> colors_;
  ColorBatches<1> overflow_;
  std::vector<LaneRef> lane_of_;
  std::vector<bool> lane_known_;
  std::vector<bool> lane_is_ball_;
  std::vector<std::uint32_t> lane_joint_;  // joint slot of every lane in visiting order
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
