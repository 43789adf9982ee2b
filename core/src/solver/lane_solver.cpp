// The joints of one lane width: packing from the colouring, the per-step anchor pass, and
// the stage loops (each colour's groups, then the overflow set in order). Generic over the
// joint registry (joints/joint_registry.hpp): no joint type is named here.
#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include "solver/four_doubles.hpp"
#include "solver/joint_batches.hpp"
#include "solver/team.hpp"
#include "world_impl.hpp"

namespace softstep {
namespace {

using solver::ColorBatches;
using solver::KernelTable;
using solver::KindBatches;
using solver::Run;

constexpr std::uint32_t kPadding = simd::kPaddingLane;

// Where a joint's lane is, for reading its impulses and refreshing it in place.
struct LaneRef {
  bool overflow = false;
  std::uint8_t kind = 0;  // index in JointKinds
  std::uint8_t variant = 0;
  std::uint32_t signature = 0;
  std::uint32_t color = 0;  // index into colors_ (non-empty colours only)
  std::uint32_t group = 0;
  std::uint32_t lane = 0;
};

// A padding lane: both bodies the static dummy, every setting zero: it applies nothing.
template <class Group>
Group empty_group() {
  Group g{};
  std::fill(std::begin(g.id), std::end(g.id), kPadding);
  return g;
}

template <int W>
void fill_common_lane(simd::AnchorLanes<W>& g, int lane, std::uint32_t slot, const JointSlot& j,
                      const BodySlots& bodies) {
  g.id[lane] = slot;
  g.body_a[lane] = solver_index(bodies[j.body_a], j.body_a);
  g.body_b[lane] = solver_index(bodies[j.body_b], j.body_b);
}

// World-frame anchors and centre offset at the step start of a group's joints, from the
// double-precision poses (far from the origin a float position has mm-sized steps, a float
// difference does not), four lanes at a time with a quaternion per lane. Eigen's quaternion
// product, called per anchor, passed its cross products through the stack and stalled on the
// reload (perf, the 100 x 100 grid); lane arrays zero-filled and then filled in place cost
// six rep stos per four joints. Built in registers, the grid's prepare took 1.05 -> 0.68 ms.
// Each lane does Eigen's operations in order (four_doubles.hpp): the lanes get the bits they
// had.
template <int W>
void write_anchors(simd::AnchorLanes<W>& g, const JointSlots& joints, const BodySlots& bodies) {
  for (int first = 0; first < W; first += 4) {
    const int count = std::min(4, W - first);
    // A lane without a joint (padding, or past the group's width) repeats a real one; only
    // real lanes are stored.
    int real = -1;
    for (int l = 0; l < count; ++l) {
      if (g.id[first + l] != kPadding) real = l;
    }
    if (real < 0) continue;
    // Per lane the fields, each element written once and made a vector by load4 or
    // load_vectors (four_doubles.hpp says why).
    double q_a[4][4], q_b[4][4];  // x, y, z, w by lane
    double local_a[3][4], local_b[3][4], position_a[3][4], position_b[3][4];
    for (int l = 0; l < 4; ++l) {
      const bool own = l < count && g.id[first + l] != kPadding;
      const JointSlot& j = joints[g.id[first + (own ? l : real)]];
      const BodySlot& a = bodies[j.body_a];
      const BodySlot& b = bodies[j.body_b];
      for (int k = 0; k < 4; ++k) {
        q_a[k][l] = a.orientation.coeffs()[k];
        q_b[k][l] = b.orientation.coeffs()[k];
      }
      for (int k = 0; k < 3; ++k) {
        local_a[k][l] = j.local_anchor_a[k];
        local_b[k][l] = j.local_anchor_b[k];
        position_a[k][l] = a.position[k];
        position_b[k][l] = b.position[k];
      }
    }
    const FourVectors r_a =
        rotate(load4(q_a[0]), load4(q_a[1]), load4(q_a[2]), load4(q_a[3]), load_vectors(local_a));
    const FourVectors r_b =
        rotate(load4(q_b[0]), load4(q_b[1]), load4(q_b[2]), load4(q_b[3]), load_vectors(local_b));
    const FourVectors center_delta{load4(position_b[0]) - load4(position_a[0]),
                                   load4(position_b[1]) - load4(position_a[1]),
                                   load4(position_b[2]) - load4(position_a[2])};
    const auto store = [&](float(&dst)[3][W], const FourVectors& v, int l) {
      dst[0][first + l] = static_cast<float>(v.x[l]);
      dst[1][first + l] = static_cast<float>(v.y[l]);
      dst[2][first + l] = static_cast<float>(v.z[l]);
    };
    for (int l = 0; l < count; ++l) {
      if (g.id[first + l] == kPadding) continue;
      store(g.r_a, r_a, l);
      store(g.r_b, r_b, l);
      store(g.center_delta, center_delta, l);
    }
  }
}

// A pass of the kernel tables, the same member of every kind's PassKernels.
enum class PassName { prepare, warm_start, solve, relax };

template <class Batches>
bool empty(const Batches& batches) {
  bool none = true;
  std::apply([&](const auto&... kind) { ((none = none && kind.groups.empty()), ...); }, batches);
  return none;
}

template <int W>
class LaneSolverImpl final : public LaneSolver {
 public:
  explicit LaneSolverImpl(KernelTable<W> kernels)
      : kernels_(std::move(kernels)),
        scalar_(solver::kernel_table<1>(solver::scalar_body_kernels())) {}

  int lanes() const override { return W; }

  void pack(const graph_coloring::GraphColoring& coloring, const JointSlots& joints,
            const BodySlots& bodies, bool specialize) override {
    colors_.clear();
    overflow_ = {};
    lane_of_.assign(joints.size(), LaneRef{});
    lane_known_.assign(joints.size(), false);
    for (int c = 0; c < graph_coloring::kColorCount; ++c) {
      const auto members = coloring.members(c);
      if (members.empty()) continue;
      ColorBatches<W> batches;
      const auto color = static_cast<std::uint32_t>(colors_.size());
      add_members<W>(batches, members, joints, bodies, specialize, false, color);
      if (!empty(batches)) colors_.push_back(std::move(batches));
    }
    add_members<1>(overflow_, coloring.overflow(), joints, bodies, specialize, true, 0);
    count_uses();
  }

  void save_impulses(JointSlots& joints) const override {
    for (std::uint32_t j = 0; j < joints.size(); ++j) {
      if (joints[j].alive && in_lanes(j)) joints[j].impulse = impulses(j);
    }
  }

  bool in_lanes(std::uint32_t joint_slot) const override {
    return joint_slot < lane_known_.size() && lane_known_[joint_slot];
  }

  std::array<float, kMaxJointImpulses> impulses(std::uint32_t joint_slot) const override {
    std::array<float, kMaxJointImpulses> out{};
    const LaneRef& r = lane_of_[joint_slot];
    with_lane(r, [&]<class Kind>(const auto& group) {
      Kind::read_impulses(group, static_cast<int>(r.lane), out.data());
    });
    return out;
  }

  bool refresh(std::uint32_t joint_slot, const JointSlots& joints, bool specialize) override {
    if (!in_lanes(joint_slot)) return false;
    const LaneRef& r = lane_of_[joint_slot];
    const JointSlot& j = joints[joint_slot];
    bool done = false;
    with_lane(r, [&]<class Kind>(auto& group) {
      if (Kind::variant(j, specialize) != r.variant || Kind::signature(j) != r.signature) return;
      Kind::fill_lane(group, static_cast<int>(r.lane), j);
      done = true;
    });
    return done;  // same kernel and signature: the plan's counts stand
  }

  bool vacate(std::uint32_t joint_slot) override {
    if (!in_lanes(joint_slot)) return false;
    const LaneRef& r = lane_of_[joint_slot];
    // The lane keeps its settings and impulses: with the dummy at both ends every effective
    // mass is zero and whatever it computes lands on a body no kernel writes.
    with_lane(r, [&]<class Kind>(auto& group) {
      group.id[r.lane] = kPadding;
      group.body_a[r.lane] = 0;
      group.body_b[r.lane] = 0;
      const KernelUse key{Kind::type, r.variant, r.signature};
      for (KernelUse& u : uses_) {
        if (u.type == key.type && u.variant == key.variant && u.signature == key.signature) {
          --u.joints;
        }
      }
    });
    lane_known_[joint_slot] = false;
    return true;
  }

  void add_impulses(std::uint32_t joint_slot, const float* delta) override {
    const LaneRef& r = lane_of_[joint_slot];
    with_lane(r, [&]<class Kind>(auto& group) {
      if constexpr (requires { Kind::add_impulses(group, 0, delta); }) {
        Kind::add_impulses(group, static_cast<int>(r.lane), delta);
      } else {
        throw std::logic_error("add_impulses: this joint kind keeps no exact-pass impulses");
      }
    });
  }

  void accumulate_geometric_inertia(const JointSlots& joints, const BodySlots& bodies,
                                    const std::vector<std::uint8_t>& dynamic, double factor,
                                    std::vector<double>& extra,
                                    const solver::Share& share) const override {
    // Colour by colour with a barrier between: a colour's joints share no dynamic body, so
    // the threads' adds never meet, and each body sums its joints in colour order whatever
    // the thread count (bit-identical). Static and kinematic bodies, which joints of one
    // colour may share, take no extra inertia: nothing reads theirs.
    const auto add = [&](std::uint32_t body, const Eigen::Vector3d& anchor, double magnitude) {
      if (dynamic[body] != 0) extra[body] += factor * magnitude * anchor.norm();
    };
    visit_lanes(
        *this, share,
        [&]<class Kind>(const auto& group, int lane, std::uint32_t slot) {
          float impulse[kMaxJointImpulses];
          Kind::read_impulses(group, lane, impulse);
          const JointSlot& j = joints[slot];
          const double magnitude = Kind::tension(j, impulse);
          if (magnitude == 0.0) return;
          if constexpr (requires { Kind::kActsOnAAtAnchorB; }) {
            // A slider's tension turns A about B's anchor, as far along A's axis as it is
            // (the fuzzer: a 1e6 N motor 74 m out along a 0.05 kg m^2 body's axis grew 10x a
            // step until NaN while A's own anchor, at its centre, gave no inertia).
            const BodySlot& a = bodies[j.body_a];
            const BodySlot& b = bodies[j.body_b];
            add(j.body_a, b.position + b.orientation * j.local_anchor_b - a.position, magnitude);
          } else {
            add(j.body_a, j.local_anchor_a, magnitude);
          }
          add(j.body_b, j.local_anchor_b, magnitude);
        },
        true);
  }

  const std::vector<KernelUse>& uses() const override { return uses_; }
  bool needs(Pass pass) const override { return needs_[static_cast<int>(pass)]; }

  void prepare(JointSlots& joints, const BodySlots& bodies, const simd::BodyArrays& arrays,
               const simd::SubstepContext& ctx, const solver::Share& share) override {
    visit_groups(*this, share, [&]<class Kind>(auto& group, int width) {
      write_anchors(group, joints, bodies);
      for (int lane = 0; lane < width; ++lane) {
        if (group.id[lane] != kPadding)
          Kind::write_step_start(group, lane, joints[group.id[lane]], bodies);
      }
    });
    for (auto& c : colors_) run_share(c, kernels_, share, PassName::prepare, arrays, ctx);
    if (share.thread == 0) {
      run_share(overflow_, scalar_, solver::Share{}, PassName::prepare, arrays, ctx);
    }
  }

  void warm_start(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                  const solver::Share& share) override {
    run_colors(share, PassName::warm_start, arrays, ctx);
  }

  void clear_impulses(const solver::Share& share) override {
    const auto clear = [&](auto& batches, const solver::Share& part) {
      JointKinds::for_each([&]<class Kind>() {
        auto& groups = std::get<JointKinds::index_of<Kind>()>(batches).groups;
        const solver::Slice s = solver::slice_of(groups.size(), part);
        for (std::size_t i = s.begin; i < s.end; ++i) Kind::clear_impulses(groups[i]);
      });
    };
    for (auto& c : colors_) clear(c, share);
    if (share.thread == 0) clear(overflow_, solver::Share{});
  }

  void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const solver::Share& share) override {
    run_colors(share, PassName::solve, arrays, ctx);
  }

  void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const solver::Share& share) override {
    run_colors(share, PassName::relax, arrays, ctx);
  }

  void integrate_velocities(SolverBodies& b, const simd::SubstepContext& ctx, bool gravity,
                            bool damping, bool torque, const solver::Share& share) override {
    const solver::Slice mine = solver::slice_of(b.blocks.size(), share);
    kernels_.bodies.integrate_velocities[gravity][damping][torque](
        b.velocity.data(), b.force.data(), b.blocks.data() + mine.begin, mine.end - mine.begin,
        ctx);
  }

  void integrate_positions(SolverBodies& b, const simd::SubstepContext& ctx,
                           const solver::Share& share) override {
    const solver::Slice mine = solver::slice_of(b.blocks.size(), share);
    kernels_.bodies.integrate_positions(b.delta.data(), b.velocity.data(),
                                        b.blocks.data() + mine.begin, mine.end - mine.begin, ctx);
  }

  void integrate_velocities_of(SolverBodies& b, RecordRuns records, const simd::SubstepContext& ctx,
                               bool gravity, bool damping, bool torque) override {
    kernels_.bodies.integrate_velocities[gravity][damping][torque](
        b.velocity.data(), b.force.data(), records.runs.data(), records.runs.size(), ctx);
    kernels_.bodies.integrate_velocity_records[gravity][damping][torque](
        b.velocity.data(), b.force.data(), records.singles.data(), records.singles.size(), ctx);
  }

  void integrate_positions_of(SolverBodies& b, RecordRuns records,
                              const simd::SubstepContext& ctx) override {
    kernels_.bodies.integrate_positions(b.delta.data(), b.velocity.data(), records.runs.data(),
                                        records.runs.size(), ctx);
    kernels_.bodies.integrate_position_records(b.delta.data(), b.velocity.data(),
                                               records.singles.data(), records.singles.size(), ctx);
  }

 private:
  template <class Group>
  static PassFn<Group> pass_of(const PassKernels<Group>& k, PassName which) {
    switch (which) {
      case PassName::prepare:
        return k.prepare;
      case PassName::warm_start:
        return k.warm_start;
      case PassName::solve:
        return k.solve;
      case PassName::relax:
        return k.relax;
    }
    return nullptr;
  }

  // This thread's share of every run of one colour (or of the overflow set) through the pass
  // of the run's variant; a variant without the pass is skipped.
  template <int V>
  static void run_share(ColorBatches<V>& c, const KernelTable<V>& table, const solver::Share& share,
                        PassName pass, const simd::BodyArrays& arrays,
                        const simd::SubstepContext& ctx) {
    JointKinds::for_each([&]<class Kind>() {
      constexpr std::size_t k = JointKinds::index_of<Kind>();
      auto& batch = std::get<k>(c);
      const auto& kernels = std::get<k>(table.joints);
      for (const Run& r : batch.runs) {
        const auto fn = pass_of(kernels[r.variant], pass);
        if (fn == nullptr) continue;
        const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
        if (slice.end > slice.begin) {
          fn(batch.groups.data() + r.begin + slice.begin, slice.end - slice.begin, arrays, ctx,
             r.signature);
        }
      }
    });
  }

  // Colour by colour, each thread its share, a barrier after each colour (joints of the next
  // colour read bodies this one wrote); then the overflow set on thread 0, in order.
  void run_colors(const solver::Share& share, PassName pass, const simd::BodyArrays& arrays,
                  const simd::SubstepContext& ctx) {
    for (auto& c : colors_) {
      run_share(c, kernels_, share, pass, arrays, ctx);
      team_barrier(share);
    }
    if (!empty(overflow_)) {
      if (share.thread == 0) run_share(overflow_, scalar_, solver::Share{}, pass, arrays, ctx);
      team_barrier(share);
    }
  }

  // f.template operator()<Kind>(group) for the group a lane reference points at.
  template <class F>
  void with_lane(const LaneRef& r, F&& f) const {
    const_cast<LaneSolverImpl*>(this)->with_lane(r, f);
  }
  template <class F>
  void with_lane(const LaneRef& r, F&& f) {
    JointKinds::for_each([&]<class Kind>() {
      constexpr std::size_t k = JointKinds::index_of<Kind>();
      if (k != r.kind) return;
      if (r.overflow) {
        f.template operator()<Kind>(std::get<k>(overflow_).groups[r.group]);
      } else {
        f.template operator()<Kind>(std::get<k>(colors_[r.color]).groups[r.group]);
      }
    });
  }

  // A joint is in the lanes unless its bodies sleep (both movable ends of a joint share an
  // island, so one end asleep means the joint is).
  static bool asleep(const JointSlot& j, const BodySlots& bodies) {
    return bodies[j.body_a].asleep || bodies[j.body_b].asleep;
  }

  // Lays out one colour's members (or the overflow set): per kind in registry order, one run
  // per (variant, signature) in that order, each packed into groups of V lanes. Members keep
  // their order within a run, so the overflow set's sequential order is the same at every
  // width.
  template <int V>
  void add_members(ColorBatches<V>& batches, std::span<const std::uint32_t> members,
                   const JointSlots& joints, const BodySlots& bodies, bool specialize,
                   bool overflow, std::uint32_t color) {
    using Key = std::pair<std::uint8_t, std::uint32_t>;  // variant, signature
    std::array<std::map<Key, std::vector<std::uint32_t>>, JointKinds::size> lists;
    for (std::uint32_t j : members) {
      if (asleep(joints[j], bodies)) continue;
      JointKinds::with(joints[j].type, [&]<class Kind>() {
        lists[JointKinds::index_of<Kind>()]
             [{Kind::variant(joints[j], specialize), Kind::signature(joints[j])}]
                 .push_back(j);
      });
    }
    JointKinds::for_each([&]<class Kind>() {
      constexpr std::size_t k = JointKinds::index_of<Kind>();
      auto& batch = std::get<k>(batches);
      using Group = typename Kind::template Group<V>;
      for (const auto& [key, list] : lists[k]) {
        const auto lanes = graph_coloring::pack_lanes(list, V, kPadding);
        const auto begin = static_cast<std::uint32_t>(batch.groups.size());
        batch.groups.resize(begin + lanes.size() / V, empty_group<Group>());
        for (std::size_t i = 0; i < lanes.size(); ++i) {
          const std::uint32_t j = lanes[i];
          const auto group = static_cast<std::uint32_t>(begin + i / V);
          const auto lane = static_cast<std::uint32_t>(i % V);
          if (j == kPadding) continue;
          fill_common_lane<V>(batch.groups[group], static_cast<int>(lane), j, joints[j], bodies);
          Kind::fill_lane(batch.groups[group], static_cast<int>(lane), joints[j]);
          lane_of_[j] = {
              overflow, static_cast<std::uint8_t>(k), key.first, key.second, color, group, lane};
          lane_known_[j] = true;
        }
        batch.runs.push_back(
            {key.first, key.second, begin, static_cast<std::uint32_t>(batch.groups.size())});
      }
    });
  }

  // Per (kind, variant, signature) in use: groups and joints (for the plan), and which passes
  // anything needs.
  void count_uses() {
    uses_.clear();
    needs_.fill(false);
    const auto count = [&](const auto& batches, int width) {
      JointKinds::for_each([&]<class Kind>() {
        const auto& batch = std::get<JointKinds::index_of<Kind>()>(batches);
        for (const Run& r : batch.runs) {
          const auto order = [](const KernelUse& x, const KernelUse& y) {
            return std::tuple(x.type, x.variant, x.signature) <
                   std::tuple(y.type, y.variant, y.signature);
          };
          KernelUse key{Kind::type, r.variant, r.signature};
          auto it = std::lower_bound(uses_.begin(), uses_.end(), key, order);
          if (it == uses_.end() || order(key, *it)) {
            key.plan = Kind::plan_kernel(r.variant, r.signature);
            key.plan.rows_per_joint = Kind::rows(r.variant, r.signature);
            it = uses_.insert(it, key);
          }
          it->batches += r.end - r.begin;
          const std::uint64_t groups = r.end - r.begin;
          it->plan.lane_bytes += groups * sizeof(batch.groups[0]);
          it->plan.impulse_bytes +=
              groups * std::uint64_t(width) * Kind::kImpulses * sizeof(float);
          for (std::uint32_t g = r.begin; g < r.end; ++g) {
            for (int lane = 0; lane < width; ++lane) {
              it->joints += batch.groups[g].id[lane] != kPadding;
            }
          }
          needs_[static_cast<int>(LaneSolver::Pass::Solve)] |=
              Kind::needs_solve(r.variant, r.signature);
          needs_[static_cast<int>(LaneSolver::Pass::Relax)] |=
              Kind::needs_relax(r.variant, r.signature);
        }
      });
    };
    for (const auto& c : colors_) count(c, W);
    count(overflow_, 1);
  }

  // Visits this thread's share of the groups of every colour, then (on thread 0 only) of the
  // overflow set, as f.template operator()<Kind>(group, width). Self is LaneSolverImpl or
  // const LaneSolverImpl. `in_colour_order`: a team barrier after each colour and after the
  // overflow set, for visits that write into shared bodies.
  template <class Self, class F>
  static void visit_groups(Self& self, const solver::Share& share, F&& f,
                           bool in_colour_order = false) {
    const auto visit = [&](auto& batches, int width, const solver::Share& part) {
      JointKinds::for_each([&]<class Kind>() {
        auto& groups = std::get<JointKinds::index_of<Kind>()>(batches).groups;
        const solver::Slice slice = solver::slice_of(groups.size(), part);
        for (std::size_t i = slice.begin; i < slice.end; ++i) {
          f.template operator()<Kind>(groups[i], width);
        }
      });
    };
    for (auto& c : self.colors_) {
      visit(c, W, share);
      if (in_colour_order) team_barrier(share);
    }
    if (share.thread == 0) visit(self.overflow_, 1, solver::Share{});
    if (in_colour_order) team_barrier(share);
  }

  // visit_groups, lane by lane: every real lane as f.template operator()<Kind>(group, lane,
  // slot).
  template <class Self, class F>
  static void visit_lanes(Self& self, const solver::Share& share, F&& f,
                          bool in_colour_order = false) {
    visit_groups(
        self, share,
        [&]<class Kind>(auto& g, int width) {
          for (int lane = 0; lane < width; ++lane) {
            if (g.id[lane] != kPadding) f.template operator()<Kind>(g, lane, g.id[lane]);
          }
        },
        in_colour_order);
  }

  KernelTable<W> kernels_;
  KernelTable<1> scalar_;
  std::vector<ColorBatches<W>> colors_;
  ColorBatches<1> overflow_;
  std::vector<LaneRef> lane_of_;
  std::vector<bool> lane_known_;
  std::vector<KernelUse> uses_;
  std::array<bool, 2> needs_{};
};

}  // namespace

bool simd_width_built(SimdWidth width) {
  switch (width) {
    case SimdWidth::Best:
    case SimdWidth::Scalar:
      return true;
    case SimdWidth::Sse:
      return SOFTSTEP_HAS_SSE;
    case SimdWidth::Avx2:
      return SOFTSTEP_HAS_AVX2;
    case SimdWidth::Avx512:
      return SOFTSTEP_HAS_AVX512;
  }
  return false;
}

bool simd_width_supported(SimdWidth width) {
  if (!simd_width_built(width)) return false;
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
    case SimdWidth::Avx512:
      // The x86-64-v4 set the 16-lane files are compiled for (core/CMakeLists.txt), with FMA in
      // every build (Eigen needs it beside AVX-512); libgcc's check includes the operating
      // system's support for the 512-bit register state.
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("fma");
  }
  return false;
}

std::string simd_width_requirement(SimdWidth width) {
  std::string isa;
  switch (width) {
    case SimdWidth::Best:
    case SimdWidth::Scalar:
      return "nothing";
    case SimdWidth::Sse:
      isa = "SSE4.2";
      break;
    case SimdWidth::Avx2:
      isa = "AVX2";
      break;
    case SimdWidth::Avx512:
      // FMA even where the build does not fuse: Eigen needs it beside AVX-512.
      isa = SOFTSTEP_USE_FMA ? "AVX-512 (F, CD, DQ, BW and VL)"
                             : "AVX-512 (F, CD, DQ, BW and VL) and FMA";
      break;
  }
  return SOFTSTEP_USE_FMA ? isa + " with FMA (this build fuses multiply-adds)" : isa;
}

// AVX-512 is the automatic choice where the CPU has it: per row it was 1.4-1.9x the AVX2
// kernels in cache on an AMD EPYC Zen 4 (softstep_kernel_bench, README "Performance"), above
// the 1.3x the issue asked for to keep it.
SimdWidth best_simd_width() {
  if (simd_width_supported(SimdWidth::Avx512)) return SimdWidth::Avx512;
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
    case SimdWidth::Avx512:
      return "avx512";
  }
  return "?";
}

std::unique_ptr<LaneSolver> make_lane_solver(SimdWidth width) {
  // A width left out of SOFTSTEP_WIDTHS has no kernels to link: its case is compiled out, and
  // World never asks for it (simd_width_supported).
  switch (width) {
    case SimdWidth::Scalar:
      return std::make_unique<LaneSolverImpl<1>>(
          solver::kernel_table<1>(solver::scalar_body_kernels()));
#if SOFTSTEP_HAS_SSE
    case SimdWidth::Sse:
      return std::make_unique<LaneSolverImpl<4>>(
          solver::kernel_table<4>(solver::sse_body_kernels()));
#endif
#if SOFTSTEP_HAS_AVX2
    case SimdWidth::Avx2:
      return std::make_unique<LaneSolverImpl<8>>(
          solver::kernel_table<8>(solver::avx2_body_kernels()));
#endif
#if SOFTSTEP_HAS_AVX512
    case SimdWidth::Avx512:
      // Bodies are integrated in blocks of 8 records (kBodyBlock), which is what the 8-lane
      // body kernels do in one step; the body passes are a small share of a step.
      return std::make_unique<LaneSolverImpl<16>>(
          solver::kernel_table<16>(solver::avx2_body_kernels()));
#endif
    default:
      break;
  }
  throw std::logic_error("make_lane_solver: width must be resolved");
}

}  // namespace softstep
