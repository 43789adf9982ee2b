// Contacts in lanes: per step, matching with the last step's impulses, a greedy colouring of
// the manifolds over their dynamic bodies, and packing by colour, signature and point count.
#include "contacts/contact_solver.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <stdexcept>
#include <tuple>

#include "contacts/contact_kernels.hpp"
#include "solver/team.hpp"
#include "world_impl.hpp"

namespace softstep {

std::size_t ContactPairHash::operator()(const ContactPairKey& k) const noexcept {
  // splitmix64-style mixing of the three words; any fixed function keeps lookups
  // deterministic (the map is never iterated in an order that matters).
  std::uint64_t h = k.low * 0x9E3779B97F4A7C15ull;
  h ^= (k.high + 0xBF58476D1CE4E5B9ull + (h << 6) + (h >> 2));
  h ^= (k.key + 0x94D049BB133111EBull + (h << 6) + (h >> 2));
  return static_cast<std::size_t>(h ^ (h >> 31));
}

ContactPairKey contact_pair_key(const ContactManifold& m) {
  const auto word = [](BodyId id) {
    return (std::uint64_t(id.generation) << 32) | std::uint64_t(id.index);
  };
  const std::uint64_t a = word(m.body_a), b = word(m.body_b);
  return {std::min(a, b), std::max(a, b), m.key};
}

std::vector<const ContactCache::value_type*> sorted_entries(const ContactCache& cache) {
  std::vector<const ContactCache::value_type*> entries;
  entries.reserve(cache.size());
  for (const auto& entry : cache) entries.push_back(&entry);
  std::sort(entries.begin(), entries.end(), [](const auto* x, const auto* y) {
    const ContactPairKey &a = x->first, &b = y->first;
    return std::tie(a.low, a.high, a.key) < std::tie(b.low, b.high, b.key);
  });
  return entries;
}

std::array<Eigen::Vector3d, 2> tangent_directions(const Eigen::Vector3d& normal) {
  // The world axis least aligned with the normal, crossed with it: well conditioned for any
  // normal, and the same normal always gives the same pair.
  const Eigen::Vector3d a = normal.cwiseAbs();
  const Eigen::Vector3d axis = a.x() <= a.y() && a.x() <= a.z()
                                   ? Eigen::Vector3d::UnitX()
                                   : (a.y() <= a.z() ? Eigen::Vector3d::UnitY()
                                                     : Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d t1 = axis.cross(normal).normalized();
  return {t1, normal.cross(t1)};
}

simd::ContactContext make_contact_context(const ContactSettings& s, float h) {
  const simd::Softness<float> spring = simd::make_softness(
      static_cast<float>(s.hertz), static_cast<float>(s.damping_ratio), h);
  return {spring.bias_rate, spring.mass_scale, spring.impulse_scale,
          static_cast<float>(s.max_push_out_speed), static_cast<float>(s.restitution_threshold)};
}

namespace {

constexpr std::uint32_t kPadding = simd::kPaddingLane;
constexpr int kContactColors = 32;  // one bit each in a body's mask
constexpr std::uint32_t kOverflow = kContactColors;

bool awake_dynamic(const BodySlot& b) {
  return b.type == BodyType::Dynamic && !b.asleep;
}

// The manifold's cached twin and the sign its impulses on B take now (-1: A and B swapped).
struct Match {
  const CachedManifold* cached = nullptr;
  double sign = 1.0;
};

Match find_match(const ContactManifold& m, const ContactCache& cache) {
  const auto it = cache.find(contact_pair_key(m));
  if (it == cache.end()) return {};
  return {&it->second, it->second.body_a == m.body_a.index ? 1.0 : -1.0};
}

// The cached point with this feature id, or -1.
int matching_point(const Match& match, std::uint32_t feature_id) {
  if (match.cached == nullptr) return -1;
  for (int k = 0; k < match.cached->point_count; ++k) {
    if (match.cached->feature_id[k] == feature_id) return k;
  }
  return -1;
}

template <class Group>
Group empty_group() {
  Group g{};
  std::fill(std::begin(g.id), std::end(g.id), kPadding);
  std::fill(std::begin(g.body_a), std::end(g.body_a), simd::kDummyBody);
  std::fill(std::begin(g.body_b), std::end(g.body_b), simd::kDummyBody);
  return g;
}

template <int W>
void put3(float (&dst)[3][W], int lane, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) dst[k][lane] = static_cast<float>(v[k]);
}

// A round shape's surface point, core + offset * n (offset = radius_a for A, -radius_b for B);
// the core itself, bit for bit, for a flat feature (radius 0).
Eigen::Vector3d surface_point(const Eigen::Vector3d& core, double offset,
                              const Eigen::Vector3d& n) {
  return offset != 0.0 ? Eigen::Vector3d(core + offset * n) : core;
}

// One manifold into one lane: the geometry in double (the anchors turned to the world at the
// step start) and the warm-start impulses from the matching cached points.
template <int W>
void fill_lane(simd::ContactLanes<W>& g, int lane, std::uint32_t index, const ContactManifold& m,
               const std::vector<BodySlot>& bodies, const ContactCache& cache, bool warm_start) {
  const BodySlot& a = bodies[m.body_a.index];
  const BodySlot& b = bodies[m.body_b.index];
  g.id[lane] = index;
  g.body_a[lane] = solver_index(a, m.body_a.index);
  g.body_b[lane] = solver_index(b, m.body_b.index);
  g.point_count[lane] = static_cast<float>(m.point_count);
  g.points = std::max(g.points, m.point_count);
  const Eigen::Vector3d& n = m.normal;
  const auto tangents = tangent_directions(n);
  put3<W>(g.normal, lane, n);
  put3<W>(g.tangent[0], lane, tangents[0]);
  put3<W>(g.tangent[1], lane, tangents[1]);
  g.friction[lane] = static_cast<float>(m.friction);
  g.restitution[lane] = static_cast<float>(m.restitution);
  g.rolling_resistance[lane] = static_cast<float>(m.rolling_resistance);
  g.tangent_speed[0][lane] = static_cast<float>(m.tangent_speed.x());
  g.tangent_speed[1][lane] = static_cast<float>(m.tangent_speed.y());
  g.radius_a[lane] = static_cast<float>(m.radius_a);
  g.radius_b[lane] = static_cast<float>(m.radius_b);
  const Match match = warm_start ? find_match(m, cache) : Match{};
  put3<W>(g.rolling_impulse, lane,
          match.cached ? Eigen::Vector3d(match.sign * match.cached->rolling_impulse)
                       : Eigen::Vector3d::Zero());
  for (int i = 0; i < m.point_count; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    auto& lanes = g.point[i];
    const Eigen::Vector3d core_a = a.orientation * p.anchor_a;
    const Eigen::Vector3d core_b = b.orientation * p.anchor_b;
    put3<W>(lanes.r_a, lane, surface_point(core_a, m.radius_a, n));
    put3<W>(lanes.r_b, lane, surface_point(core_b, -m.radius_b, n));
    lanes.base_separation[lane] = static_cast<float>(p.separation - n.dot(core_b - core_a));
    const int k = matching_point(match, p.feature_id);
    double normal = 0.0;
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();
    if (k >= 0) {
      normal = match.cached->normal_impulse[static_cast<std::size_t>(k)];
      friction = match.sign * match.cached->friction_impulse[static_cast<std::size_t>(k)];
    }
    lanes.normal_impulse[lane] = static_cast<float>(normal);
    lanes.tangent_impulse[0][lane] = static_cast<float>(tangents[0].dot(friction));
    lanes.tangent_impulse[1][lane] = static_cast<float>(tangents[1].dot(friction));
  }
}

// A lane's impulses as the reading and the cache entry of its manifold.
template <int W>
void read_lane(const simd::ContactLanes<W>& g, int lane, const ContactManifold& m,
               const ContactCache& previous, ContactReading& reading, CachedManifold& next) {
  const auto get3 = [&](const float(&src)[3][W]) {
    return Eigen::Vector3d(src[0][lane], src[1][lane], src[2][lane]);
  };
  const Eigen::Vector3d t1 = get3(g.tangent[0]);
  const Eigen::Vector3d t2 = get3(g.tangent[1]);
  const Match match = find_match(m, previous);
  next.body_a = m.body_a.index;
  next.point_count = m.point_count;
  next.rolling_impulse = get3(g.rolling_impulse);
  reading.rolling_impulse = next.rolling_impulse;
  for (int i = 0; i < m.point_count; ++i) {
    const auto& p = g.point[i];
    const auto s = static_cast<std::size_t>(i);
    next.feature_id[s] = m.points[s].feature_id;
    next.normal_impulse[s] = p.normal_impulse[lane];
    next.friction_impulse[s] =
        double(p.tangent_impulse[0][lane]) * t1 + double(p.tangent_impulse[1][lane]) * t2;
    next.max_normal_impulse[s] = p.max_normal_impulse[lane];
    reading.points[s] = {next.normal_impulse[s], next.friction_impulse[s],
                         next.max_normal_impulse[s],
                         matching_point(match, m.points[s].feature_id) < 0};
  }
}

// A manifold left out of the lanes (both ends static or asleep): it keeps what it had.
void carry_over(const ContactManifold& m, const ContactCache& previous, ContactReading& reading,
                CachedManifold& next) {
  const Match match = find_match(m, previous);
  next = CachedManifold{};
  next.body_a = m.body_a.index;
  next.point_count = m.point_count;
  if (match.cached) next.rolling_impulse = match.sign * match.cached->rolling_impulse;
  reading.rolling_impulse = next.rolling_impulse;
  for (int i = 0; i < m.point_count; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const int k = matching_point(match, m.points[s].feature_id);
    next.feature_id[s] = m.points[s].feature_id;
    if (k >= 0) {
      const auto c = static_cast<std::size_t>(k);
      next.normal_impulse[s] = match.cached->normal_impulse[c];
      next.friction_impulse[s] = match.sign * match.cached->friction_impulse[c];
    }
    reading.points[s] = {next.normal_impulse[s], next.friction_impulse[s], 0.0, k < 0};
  }
}

enum class ContactPass { prepare, warm_start, solve, relax, restitute };

template <int W>
typename solver::ContactKernels<W>::Pass pass_of(const solver::ContactKernels<W>& k,
                                                  ContactPass pass, std::uint32_t signature) {
  switch (pass) {
    case ContactPass::prepare:
      return k.prepare[signature];
    case ContactPass::warm_start:
      return k.warm_start[signature];
    case ContactPass::solve:
      return k.solve[signature];
    case ContactPass::relax:
      return k.relax[signature];
    case ContactPass::restitute:
      return k.restitute;
  }
  return nullptr;
}

struct ContactRun {
  std::uint32_t signature;
  std::uint32_t begin, end;  // groups
};

// The groups of one colour (or of the overflow set) at width W, cut into runs by signature.
template <int W>
struct ContactBatch {
  std::vector<simd::ContactLanes<W>> groups;
  std::vector<ContactRun> runs;
};

template <int W>
class ContactSolverImpl final : public ContactSolver {
 public:
  ContactSolverImpl(solver::ContactKernels<W> kernels, solver::ContactKernels<1> scalar)
      : kernels_(kernels), scalar_(scalar) {}

  void load(std::span<const ContactManifold> manifolds, const std::vector<BodySlot>& bodies,
            const ContactCache& cache, bool warm_start) override {
    const auto start = std::chrono::steady_clock::now();
    layout_ = {};
    used_colors_ = 0;
    entries_.clear();
    if (body_colors_.size() < bodies.size()) body_colors_.resize(bodies.size(), 0u);
    for (std::uint32_t i = 0; i < manifolds.size(); ++i) {
      const ContactManifold& m = manifolds[i];
      const std::uint32_t a = m.body_a.index, b = m.body_b.index;
      const bool moves_a = awake_dynamic(bodies[a]), moves_b = awake_dynamic(bodies[b]);
      if (!moves_a && !moves_b) continue;
      std::uint32_t signature = 0;
      if (m.friction > 0.0) signature |= simd::kContactFriction;
      if (m.rolling_resistance > 0.0) signature |= simd::kContactRolling;
      layout_.signatures |= signature;
      layout_.restitution |= m.restitution > 0.0;
      layout_.points += static_cast<std::uint32_t>(m.point_count);
      // Greedy colouring in input order: the lowest colour neither dynamic body has yet.
      // Static and kinematic bodies are never written by a contact, so they bind nothing.
      const std::uint32_t taken = (moves_a ? body_colors_[a] : 0u) | (moves_b ? body_colors_[b] : 0u);
      std::uint32_t color = kOverflow;
      if (taken != ~0u) {
        color = static_cast<std::uint32_t>(std::countr_one(taken));
        if (moves_a) body_colors_[a] |= 1u << color;
        if (moves_b) body_colors_[b] |= 1u << color;
        used_colors_ |= 1ull << color;
      }
      entries_.push_back({color, signature, kMaxContactPoints - m.point_count, i});
    }
    for (const Entry& e : entries_) {
      const ContactManifold& m = manifolds[e.manifold];
      body_colors_[m.body_a.index] = 0;
      body_colors_[m.body_b.index] = 0;
    }
    // Colour, then signature (a run per kernel variant), then most points first (a group's
    // point loop stops at its fullest lane). Stable: the overflow keeps input order within.
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& x, const Entry& y) {
      return std::tie(x.color, x.signature, x.fewer_points) <
             std::tie(y.color, y.signature, y.fewer_points);
    });
    layout_.manifolds = static_cast<std::uint32_t>(entries_.size());
    layout_.colors = static_cast<std::uint32_t>(std::popcount(used_colors_));
    colors_.resize(static_cast<std::size_t>(layout_.colors));
    for (auto& c : colors_) {
      c.groups.clear();
      c.runs.clear();
    }
    overflow_.groups.clear();
    overflow_.runs.clear();
    std::size_t begin = 0;
    std::uint32_t color_index = 0;
    while (begin < entries_.size()) {
      std::size_t end = begin;
      const std::uint32_t color = entries_[begin].color;
      while (end < entries_.size() && entries_[end].color == color) ++end;
      if (color == kOverflow) {
        layout_.overflow = static_cast<std::uint32_t>(end - begin);
        pack<1>(overflow_, begin, end, manifolds, bodies, cache, warm_start);
      } else {
        pack<W>(colors_[color_index++], begin, end, manifolds, bodies, cache, warm_start);
      }
      begin = end;
    }
    layout_.load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
  }

  const ContactLayout& layout() const override { return layout_; }

  void prepare(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
               const solver::Share& share) override {
    for (auto& c : colors_) run_share<W>(c, kernels_, share, ContactPass::prepare, arrays, ctx, {});
    if (share.thread == 0) {
      run_share<1>(overflow_, scalar_, solver::Share{}, ContactPass::prepare, arrays, ctx, {});
    }
  }
  void warm_start(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                  const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::warm_start, arrays, ctx, cc);
  }
  void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::solve, arrays, ctx, cc);
  }
  void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::relax, arrays, ctx, cc);
  }
  void restitute(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                 const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::restitute, arrays, ctx, cc);
  }

  void store(std::span<const ContactManifold> manifolds, const ContactCache& previous,
             ContactCache& next, std::vector<ContactReading>& readings) const override {
    next.clear();
    next.reserve(manifolds.size());
    readings.assign(manifolds.size(), ContactReading{});
    in_lanes_.assign(manifolds.size(), false);
    const auto read = [&](const auto& batch, auto width) {
      for (const auto& g : batch.groups) {
        for (int lane = 0; lane < decltype(width)::value; ++lane) {
          if (g.id[lane] == kPadding) continue;
          const ContactManifold& m = manifolds[g.id[lane]];
          ContactReading& r = readings[g.id[lane]];
          r.body_a = m.body_a;
          r.body_b = m.body_b;
          r.point_count = m.point_count;
          read_lane<decltype(width)::value>(g, lane, m, previous, r, next[contact_pair_key(m)]);
          in_lanes_[g.id[lane]] = true;
        }
      }
    };
    for (const auto& c : colors_) read(c, std::integral_constant<int, W>{});
    read(overflow_, std::integral_constant<int, 1>{});
    for (std::uint32_t i = 0; i < manifolds.size(); ++i) {
      if (in_lanes_[i]) continue;
      const ContactManifold& m = manifolds[i];
      readings[i].body_a = m.body_a;
      readings[i].body_b = m.body_b;
      readings[i].point_count = m.point_count;
      carry_over(m, previous, readings[i], next[contact_pair_key(m)]);
    }
  }

 private:
  struct Entry {
    std::uint32_t color, signature;
    int fewer_points;  // kMaxContactPoints - points: sorts the fullest first
    std::uint32_t manifold;
  };

  template <int V>
  void pack(ContactBatch<V>& batch, std::size_t begin, std::size_t end,
            std::span<const ContactManifold> manifolds, const std::vector<BodySlot>& bodies,
            const ContactCache& cache, bool warm_start) {
    for (std::size_t run_begin = begin; run_begin < end;) {
      const std::uint32_t signature = entries_[run_begin].signature;
      std::size_t run_end = run_begin;
      while (run_end < end && entries_[run_end].signature == signature) ++run_end;
      const auto first = static_cast<std::uint32_t>(batch.groups.size());
      const std::size_t count = run_end - run_begin;
      batch.groups.resize(first + (count + V - 1) / V,
                          empty_group<simd::ContactLanes<V>>());
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t index = entries_[run_begin + i].manifold;
        fill_lane<V>(batch.groups[first + i / V], static_cast<int>(i % V), index,
                     manifolds[index], bodies, cache, warm_start);
      }
      batch.runs.push_back({signature, first, static_cast<std::uint32_t>(batch.groups.size())});
      run_begin = run_end;
    }
  }

  template <int V>
  static void run_share(ContactBatch<V>& batch, const solver::ContactKernels<V>& kernels,
                        const solver::Share& share, ContactPass pass,
                        const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                        const simd::ContactContext& cc) {
    for (const ContactRun& r : batch.runs) {
      const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
      if (slice.end > slice.begin) {
        pass_of<V>(kernels, pass, r.signature)(batch.groups.data() + r.begin + slice.begin,
                                               slice.end - slice.begin, arrays, ctx, cc);
      }
    }
  }

  // As the joints: colour by colour with a barrier after each, then the overflow in order.
  void run_colors(const solver::Share& share, ContactPass pass, const simd::BodyArrays& arrays,
                  const simd::SubstepContext& ctx, const simd::ContactContext& cc) {
    for (auto& c : colors_) {
      run_share<W>(c, kernels_, share, pass, arrays, ctx, cc);
      solver::team_barrier(share);
    }
    if (!overflow_.groups.empty()) {
      if (share.thread == 0) run_share<1>(overflow_, scalar_, solver::Share{}, pass, arrays, ctx, cc);
      solver::team_barrier(share);
    }
  }

  solver::ContactKernels<W> kernels_;
  solver::ContactKernels<1> scalar_;
  ContactLayout layout_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> body_colors_;  // per body slot, scratch of load (all zero between)
  std::uint64_t used_colors_ = 0;
  std::vector<ContactBatch<W>> colors_;
  ContactBatch<1> overflow_;
  mutable std::vector<bool> in_lanes_;  // scratch of store
};

}  // namespace

std::unique_ptr<ContactSolver> make_contact_solver(SimdWidth width) {
  switch (width) {
    case SimdWidth::Scalar:
      return std::make_unique<ContactSolverImpl<1>>(solver::scalar_contact_kernels(),
                                                    solver::scalar_contact_kernels());
    // Widths left out of SOFTSTEP_WIDTHS are compiled out (make_lane_solver says why).
#if SOFTSTEP_HAS_SSE
    case SimdWidth::Sse:
      return std::make_unique<ContactSolverImpl<4>>(solver::sse_contact_kernels(),
                                                    solver::scalar_contact_kernels());
#endif
#if SOFTSTEP_HAS_AVX2
    case SimdWidth::Avx2:
      return std::make_unique<ContactSolverImpl<8>>(solver::avx2_contact_kernels(),
                                                    solver::scalar_contact_kernels());
#endif
#if SOFTSTEP_HAS_AVX512
    case SimdWidth::Avx512:
      return std::make_unique<ContactSolverImpl<16>>(solver::avx512_contact_kernels(),
                                                     solver::scalar_contact_kernels());
#endif
    default:
      break;
  }
  throw std::logic_error("make_contact_solver: width must be resolved");
}

}  // namespace softstep
