// Contacts in lanes: per step, matching with the last step's impulses, a greedy colouring of
// the manifolds over their dynamic bodies, and packing by colour, signature and point count.
#include "contacts/contact_solver.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "contacts/contact_kernels.hpp"
#include "elapsed_ms.hpp"
#include "prefetch.hpp"
#include "solver/four_doubles.hpp"
#include "solver/team.hpp"
#include "world_impl.hpp"

namespace softstep {

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

Match find_match(const ContactManifold& m, const ContactPairKey& key, std::uint32_t index,
                 const ContactCache& cache) {
  const ContactCacheEntry* entry = cache.find(key, index);
  if (entry == nullptr) return {};
  return {&entry->manifold, entry->manifold.body_a == m.body_a.index ? 1.0 : -1.0};
}

// The cached point with this feature id, or -1.
int matching_point(const Match& match, std::uint32_t feature_id) {
  if (match.cached == nullptr) return -1;
  for (int k = 0; k < match.cached->point_count; ++k) {
    if (match.cached->feature_id[k] == feature_id) return k;
  }
  return -1;
}

// What reading a lane back needs of its manifold besides the lanes, written while packing in
// the solver's order: reading back then walks these in order instead of returning to each
// manifold at random (one cache line here against six).
struct PackedManifold {
  ContactPairKey key;
  Match match;
  std::array<std::uint32_t, kMaxContactPoints> feature_id;
  std::uint16_t point_count;
  std::uint16_t new_points;  // CachedManifold::new_points
  bool a_is_low;             // body A is key.low (else key.high)
};

PackedManifold packed_manifold(const ContactManifold& m, std::uint32_t index,
                               const ContactCache& previous) {
  PackedManifold packed{};
  packed.key = contact_pair_key(m);
  packed.match = find_match(m, packed.key, index, previous);
  packed.point_count = static_cast<std::uint16_t>(m.point_count);
  packed.a_is_low = packed.key.low == body_word(m.body_a);
  for (int i = 0; i < m.point_count; ++i) {
    const std::uint32_t feature = m.points[static_cast<std::size_t>(i)].feature_id;
    packed.feature_id[static_cast<std::size_t>(i)] = feature;
    if (matching_point(packed.match, feature) < 0) packed.new_points |= static_cast<std::uint16_t>(1u << i);
  }
  return packed;
}

// Lanes are filled and read in the solver's order (by colour), so the manifolds and their
// bodies are met at random places: each is asked from memory this many manifolds ahead, so
// that the misses overlap instead of stalling one after another. (Last step's cache entries
// are in the solver's order, met front to back where the scene kept its order: fetching them
// too made the pyramid's prepare 0.04-0.08 ms slower, 4 runs alternated, 2026-11-27.)
constexpr std::size_t kFetchAhead = 8;

// Manifolds per chunk of packing that a thread takes at a time (ContactSolverImpl::pack): a
// few microseconds of work, against an atomic add per chunk.
constexpr std::uint32_t kPackChunk = 64;

// Makes every lane of the group padding, in place: building an empty group and assigning it
// wrote each byte twice (5.6 KB a group at 16 lanes; the copy held a fifth of the packing's
// perf samples, though the pyramid's prepare shortened by less than the host's noise).
template <class Group>
void empty_in_place(Group& g) {
  static_assert(std::is_trivially_copyable_v<Group>, "cleared with memset");
  std::memset(&g, 0, sizeof g);
  std::fill(std::begin(g.id), std::end(g.id), kPadding);
  std::fill(std::begin(g.body_a), std::end(g.body_a), simd::kDummyBody);
  std::fill(std::begin(g.body_b), std::end(g.body_b), simd::kDummyBody);
}

template <int W>
void put3(float (&dst)[3][W], int lane, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) dst[k][lane] = static_cast<float>(v[k]);
}

// One double per contact point of a manifold: the point loop's geometry runs on all of them at
// once instead of calling Eigen's quaternion product (out of line here) once per anchor. Each
// lane does the scalar formula's operations in the same order, so every lane holds the bits
// the scalar code gave (the contact golden hashes and the pyramid's state hash are unchanged).
// The pack took 3-11 % less time for it (alternated by step in one process, 2026-11-26).
static_assert(kMaxContactPoints == 4, "one lane per point");

// A round shape's surface point, core + offset * n (offset = radius_a for A, -radius_b for B);
// the core itself, bit for bit, for a flat feature (radius 0).
FourVectors surface_points(const FourVectors& core, double offset, const Eigen::Vector3d& n) {
  if (offset == 0.0) return core;
  return {core.x + offset * n.x(), core.y + offset * n.y(), core.z + offset * n.z()};
}

// The kernels solve in the frame (t1, t2, n), which must be a rotation: the normal is checked
// unit to 1e-4 (contact_validation.cpp) and made unit here, unless it already is to far below
// float precision (a normalized double normal: the square root and division sit on the
// packing's critical path, 15,000 times a step on the pyramid).
Eigen::Vector3d unit_normal(const Eigen::Vector3d& n) {
  const double length2 = n.squaredNorm();
  return std::abs(length2 - 1.0) <= 1e-12 ? n : Eigen::Vector3d(n / std::sqrt(length2));
}

// World vectors in the manifold's frame (t1, t2, n): their coordinates along each axis.
FourVectors in_frame(const std::array<Eigen::Vector3d, 2>& tangents, const Eigen::Vector3d& n,
                     const FourVectors& v) {
  const auto along = [&](const Eigen::Vector3d& axis) {
    return (axis.x() * v.x + axis.y() * v.y) + axis.z() * v.z;
  };
  return {along(tangents[0]), along(tangents[1]), along(n)};
}

template <int W>
void put3(float (&dst)[3][W], int lane, const FourVectors& v, int point) {
  dst[0][lane] = static_cast<float>(v.x[point]);
  dst[1][lane] = static_cast<float>(v.y[point]);
  dst[2][lane] = static_cast<float>(v.z[point]);
}

// One manifold into one lane: the geometry in double (the anchors turned to the world at the
// step start) and the warm-start impulses from the matching cached points (none: match empty).
template <int W>
void fill_lane(simd::ContactLanes<W>& g, int lane, std::uint32_t index, const ContactManifold& m,
               const BodySlots& bodies, const Match& match) {
  const BodySlot& a = bodies[m.body_a.index];
  const BodySlot& b = bodies[m.body_b.index];
  g.id[lane] = index;
  g.body_a[lane] = solver_index(a, m.body_a.index);
  g.body_b[lane] = solver_index(b, m.body_b.index);
  g.point_count[lane] = static_cast<float>(m.point_count);
  g.points = std::max(g.points, m.point_count);
  const Eigen::Vector3d n = unit_normal(m.normal);
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
  if (match.cached) {
    const Eigen::Vector3d rolling = match.sign * match.cached->rolling_impulse;
    put3<W>(g.rolling_impulse, lane,
            Eigen::Vector3d(tangents[0].dot(rolling), tangents[1].dot(rolling), n.dot(rolling)));
  }
  // One point's anchors per lane; lanes past point_count hold 0 and are not stored. Each
  // element written once and made a vector by load_vectors (four_doubles.hpp says why).
  double along_a[3][4], along_b[3][4];  // axis, then point
  for (int i = 0; i < 4; ++i) {
    const bool real = i < m.point_count;
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      along_a[k][i] = real ? p.anchor_a[k] : 0.0;
      along_b[k][i] = real ? p.anchor_b[k] : 0.0;
    }
  }
  const Eigen::Quaterniond& q_a = a.orientation;
  const Eigen::Quaterniond& q_b = b.orientation;
  const FourVectors core_a = rotate(q_a.x(), q_a.y(), q_a.z(), q_a.w(), load_vectors(along_a));
  const FourVectors core_b = rotate(q_b.x(), q_b.y(), q_b.z(), q_b.w(), load_vectors(along_b));
  const FourVectors r_a = surface_points(core_a, m.radius_a, n);
  const FourVectors r_b = surface_points(core_b, -m.radius_b, n);
  // n . (core_b - core_a), summed as Eigen's dot sums three terms.
  const FourDoubles along_normal = (n.x() * (core_b.x - core_a.x) + n.y() * (core_b.y - core_a.y)) +
                                   n.z() * (core_b.z - core_a.z);
  const FourVectors frame_r_a = in_frame(tangents, n, r_a);
  const FourVectors frame_r_b = in_frame(tangents, n, r_b);
  for (int i = 0; i < m.point_count; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    auto& lanes = g.point[i];
    put3<W>(lanes.r_a, lane, frame_r_a, i);
    put3<W>(lanes.r_b, lane, frame_r_b, i);
    lanes.base_separation[lane] = static_cast<float>(p.separation - along_normal[i]);
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

// A lane's impulses as its manifold's entry in the next cache (which is also what the
// readings are read from, on demand: read_out).
template <int W>
void read_lane(const simd::ContactLanes<W>& g, int lane, const PackedManifold& packed,
               ContactCacheEntry& next_entry) {
  const auto get3 = [&](const float(&src)[3][W]) {
    return Eigen::Vector3d(src[0][lane], src[1][lane], src[2][lane]);
  };
  const Eigen::Vector3d t1 = get3(g.tangent[0]);
  const Eigen::Vector3d t2 = get3(g.tangent[1]);
  next_entry.key = packed.key;
  CachedManifold& next = next_entry.manifold;
  next = CachedManifold{};
  next.body_a = static_cast<std::uint32_t>(packed.a_is_low ? packed.key.low : packed.key.high);
  next.point_count = packed.point_count;
  next.new_points = packed.new_points;
  const Eigen::Vector3d rolling = get3(g.rolling_impulse);  // in the manifold's frame
  if (!rolling.isZero(0.0)) {
    next.rolling_impulse = rolling.x() * t1 + rolling.y() * t2 + rolling.z() * get3(g.normal);
  }
  for (int i = 0; i < packed.point_count; ++i) {
    const auto& p = g.point[i];
    const auto s = static_cast<std::size_t>(i);
    next.feature_id[s] = packed.feature_id[s];
    next.normal_impulse[s] = p.normal_impulse[lane];
    next.friction_impulse[s] =
        double(p.tangent_impulse[0][lane]) * t1 + double(p.tangent_impulse[1][lane]) * t2;
    next.max_normal_impulse[s] = p.max_normal_impulse[lane];
  }
}

// A manifold left out of the lanes (both ends static or asleep): it keeps what it had.
void carry_over(const ContactManifold& m, const Match& match, CachedManifold& next) {
  next = CachedManifold{};
  next.body_a = m.body_a.index;
  next.point_count = static_cast<std::uint16_t>(m.point_count);
  if (match.cached) next.rolling_impulse = match.sign * match.cached->rolling_impulse;
  for (int i = 0; i < m.point_count; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const int k = matching_point(match, m.points[s].feature_id);
    next.feature_id[s] = m.points[s].feature_id;
    if (k >= 0) {
      const auto c = static_cast<std::size_t>(k);
      next.normal_impulse[s] = match.cached->normal_impulse[c];
      next.friction_impulse[s] = match.sign * match.cached->friction_impulse[c];
    } else {
      next.new_points |= static_cast<std::uint16_t>(1u << i);
    }
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
  std::uint32_t begin, end;              // groups
  std::uint32_t first_entry, end_entry;  // its manifolds, in the solver's order
};

// The groups of one colour (or of the overflow set) at width W, cut into runs by signature.
template <int W>
struct ContactBatch {
  PagedVector<simd::ContactLanes<W>> groups;
  std::vector<ContactRun> runs;
};

// The solver's order: colour, then signature (a run per kernel variant), then most points
// first (a group's point loop stops at its fullest lane), as one small number; a counting sort
// by it is stable, so the overflow keeps input order within.
constexpr std::uint32_t kPointOrders = kMaxContactPoints;
constexpr std::uint32_t kOrderKeys = (kContactColors + 1) * simd::kContactSignatures * kPointOrders;

constexpr std::uint32_t order_key(std::uint32_t color, std::uint32_t signature, int points) {
  return (color * simd::kContactSignatures + signature) * kPointOrders +
         static_cast<std::uint32_t>(kMaxContactPoints - points);
}
constexpr std::uint32_t color_of(std::uint32_t key) {
  return key / (simd::kContactSignatures * kPointOrders);
}
constexpr std::uint32_t signature_of(std::uint32_t key) {
  return key / kPointOrders % simd::kContactSignatures;
}

template <int W>
class ContactSolverImpl final : public ContactSolver {
 public:
  ContactSolverImpl(solver::ContactKernels<W> kernels, solver::ContactKernels<1> scalar)
      : kernels_(kernels), scalar_(scalar) {}

  bool load(const ContactStep& step, bool same_inputs) override {
    const auto start = std::chrono::steady_clock::now();
    step_ = step;
    if (same_inputs && layout_inputs(step.bodies_version, step.manifolds.size()) != nullptr) {
      // The layout is a function of its inputs alone: what it was, bit for bit.
      place_in_next_cache(step);
      next_pack_chunk_.store(0, std::memory_order_relaxed);
      layout_.kept = true;
      layout_.same_inputs = true;
      layout_.load_ms = ms_since(start);
      return true;
    }
    const std::span<const ContactManifold> manifolds = step.manifolds;
    const BodySlots& bodies = *step.bodies;
    layout_ = {};
    used_colors_ = 0;
    unsorted_.clear();
    left_out_.clear();
    // Whether these inputs are the last layout's, found as they replace them.
    bool unchanged = inputs_valid_ && step.bodies_version == inputs_version_ &&
                     inputs_.size() == manifolds.size();
    inputs_.resize(manifolds.size());
    inputs_valid_ = false;
    if (body_colors_.size() < bodies.size()) body_colors_.resize(bodies.size(), 0u);
    for (std::uint32_t i = 0; i < manifolds.size(); ++i) {
      const ContactManifold& m = manifolds[i];
      const std::uint32_t a = m.body_a.index, b = m.body_b.index;
      if (a >= bodies.size() || b >= bodies.size() || m.point_count < 1 ||
          m.point_count > kMaxContactPoints) {
        clear_body_colors(manifolds);
        layout_ = {};
        return false;
      }
      const ContactLayoutInput input = contact_layout_input(m);
      unchanged &= input == inputs_[i];
      inputs_[i] = input;
      const bool moves_a = awake_dynamic(bodies[a]), moves_b = awake_dynamic(bodies[b]);
      if (!moves_a && !moves_b) {
        left_out_.push_back(i);
        continue;
      }
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
      unsorted_.push_back({order_key(color, signature, m.point_count), i});
    }
    clear_body_colors(manifolds);
    sort_entries();
    layout_.manifolds = static_cast<std::uint32_t>(entries_.size());
    layout_.colors = static_cast<std::uint32_t>(std::popcount(used_colors_));
    if (colors_.size() < layout_.colors) colors_.resize(layout_.colors);
    overflow_.groups.clear();
    overflow_.runs.clear();
    std::size_t begin = 0;
    std::uint32_t color_index = 0;
    while (begin < entries_.size()) {
      std::size_t end = begin;
      const std::uint32_t color = color_of(entries_[begin].order);
      while (end < entries_.size() && color_of(entries_[end].order) == color) ++end;
      if (color == kOverflow) {
        layout_.overflow = static_cast<std::uint32_t>(end - begin);
        lay_out<1>(overflow_, begin, end);
      } else {
        lay_out<W>(colors_[color_index++], begin, end);
      }
      begin = end;
    }
    cut_pack_chunks();
    packed_.resize(entries_.size());
    place_in_next_cache(step);
    inputs_valid_ = true;
    inputs_version_ = step.bodies_version;
    layout_.same_inputs = unchanged;
    layout_.load_ms = ms_since(start);
    return true;
  }

  const ContactLayout& layout() const override { return layout_; }

  void pack(const solver::Share& share) override {
    // Chunks taken in turn rather than a fixed half each: the thread that idled through the
    // caller's collision wakes with cold caches and packed its half in 1.4-2.3 ms against the
    // caller's 1.0-1.1 (the pyramid, 2026-11-26), and the stage waited for it. Which thread
    // fills a group changes nothing in it.
    for (;;) {
      const std::size_t i = next_pack_chunk_.fetch_add(1, std::memory_order_relaxed);
      if (i >= pack_chunks_.size()) break;
      const PackChunk& chunk = pack_chunks_[i];
      ContactBatch<W>& batch = colors_[chunk.color];
      pack_groups<W>(batch, batch.runs[chunk.run], chunk.begin, chunk.end);
    }
    pack_share<1>(overflow_, share);
  }

  void prepare(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
               const solver::Share& share) override {
    for (std::uint32_t c = 0; c < layout_.colors; ++c) {
      run_share<W>(colors_[c], kernels_, share, ContactPass::prepare, arrays, ctx, {});
    }
    if (share.thread == 0) {
      run_share<1>(overflow_, scalar_, solver::Share{}, ContactPass::prepare, arrays, ctx, {});
    }
  }
  void warm_start(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                  const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::warm_start, arrays, ctx, cc);
  }
  void clear_impulses(const solver::Share& share) override {
    for (std::uint32_t c = 0; c < layout_.colors; ++c) clear_share<W>(colors_[c], share);
    if (share.thread == 0) clear_share<1>(overflow_, solver::Share{});
  }
  void solve(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const simd::ContactContext& cc, bool friction, const solver::Share& share) override {
    // Without friction a group runs its signature's variant without the friction rows; its
    // friction impulses stay as the warm start left them.
    run_colors(share, ContactPass::solve, arrays, ctx, cc,
               friction ? ~0u : ~std::uint32_t{simd::kContactFriction});
  }
  void relax(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
             const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::relax, arrays, ctx, cc);
  }
  void restitute(const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                 const simd::ContactContext& cc, const solver::Share& share) override {
    run_colors(share, ContactPass::restitute, arrays, ctx, cc);
  }

  void store(const solver::Share& share) override {
    for (std::uint32_t c = 0; c < layout_.colors; ++c) store_share<W>(colors_[c], share);
    store_share<1>(overflow_, share);
    const solver::Slice mine = solver::slice_of(left_out_.size(), share);
    for (std::size_t k = mine.begin; k < mine.end; ++k) {
      const std::uint32_t index = left_out_[k];
      const ContactManifold& m = step_.manifolds[index];
      ContactCacheEntry& next = step_.next->slot_entry(entries_.size() + k);
      next.key = contact_pair_key(m);
      carry_over(m, find_match(m, next.key, index, *step_.previous), next.manifold);
    }
  }

  const ContactLayoutInput* layout_inputs(std::uint64_t bodies_version,
                                          std::size_t manifolds) const override {
    const bool valid =
        inputs_valid_ && bodies_version == inputs_version_ && inputs_.size() == manifolds;
    return valid ? inputs_.data() : nullptr;
  }

 private:
  struct Entry {
    std::uint32_t order;  // order_key
    std::uint32_t manifold;
  };

  // Each manifold's slot in the next cache, written by the team: the entries in the solver's
  // order (what the next step's packing and read-back walk front to back when the scene keeps
  // its order; contact_cache.hpp), then the manifolds left out.
  void place_in_next_cache(const ContactStep& step) const {
    step.next->size_for_step(step.manifolds.size());
    for (std::size_t e = 0; e < entries_.size(); ++e) {
      step.next->place(entries_[e].manifold, static_cast<std::uint32_t>(e));
    }
    for (std::size_t k = 0; k < left_out_.size(); ++k) {
      step.next->place(left_out_[k], static_cast<std::uint32_t>(entries_.size() + k));
    }
  }

  // body_colors_ back to all zero: only the bodies of the manifolds coloured have bits.
  void clear_body_colors(std::span<const ContactManifold> manifolds) {
    for (const Entry& e : unsorted_) {
      const ContactManifold& m = manifolds[e.manifold];
      body_colors_[m.body_a.index] = 0;
      body_colors_[m.body_b.index] = 0;
    }
  }

  void sort_entries() {
    counts_.fill(0);
    for (const Entry& e : unsorted_) ++counts_[e.order];
    std::uint32_t sum = 0;
    for (std::uint32_t& c : counts_) sum += std::exchange(c, sum);
    entries_.resize(unsorted_.size());
    for (const Entry& e : unsorted_) entries_[counts_[e.order]++] = e;
  }

  // The runs and group count of entries [begin, end) (one colour, or the overflow).
  template <int V>
  void lay_out(ContactBatch<V>& batch, std::size_t begin, std::size_t end) {
    batch.runs.clear();
    std::uint32_t groups = 0;
    for (std::size_t run_begin = begin; run_begin < end;) {
      const std::uint32_t signature = signature_of(entries_[run_begin].order);
      std::size_t run_end = run_begin;
      while (run_end < end && signature_of(entries_[run_end].order) == signature) ++run_end;
      const auto count = static_cast<std::uint32_t>(run_end - run_begin);
      const std::uint32_t first = groups;
      groups += (count + V - 1) / V;
      batch.runs.push_back({signature, first, groups, static_cast<std::uint32_t>(run_begin),
                            static_cast<std::uint32_t>(run_end)});
      run_begin = run_end;
    }
    batch.groups.resize(groups);
  }

  template <int V>
  void pack_share(ContactBatch<V>& batch, const solver::Share& share) {
    for (const ContactRun& r : batch.runs) {
      const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
      pack_groups<V>(batch, r, slice.begin, slice.end);
    }
  }

  // Groups [begin, end) of run r (counted from the run's first).
  template <int V>
  void pack_groups(ContactBatch<V>& batch, const ContactRun& r, std::size_t begin,
                   std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      simd::ContactLanes<V>& g = batch.groups[r.begin + k];
      empty_in_place(g);
      const std::size_t first = r.first_entry + k * V;
      const std::size_t last = std::min<std::size_t>(first + V, r.end_entry);
      for (std::size_t e = first; e < last; ++e) {
        if (e + kFetchAhead < r.end_entry) fetch_for_packing(entries_[e + kFetchAhead].manifold);
        const std::uint32_t index = entries_[e].manifold;
        const ContactManifold& m = step_.manifolds[index];
        packed_[e] = packed_manifold(m, index, *step_.previous);
        fill_lane<V>(g, static_cast<int>(e - first), index, m, *step_.bodies,
                     step_.warm_start ? packed_[e].match : Match{});
      }
    }
  }

  // The colours' groups in chunks of about kPackChunk manifolds, in the solver's order.
  void cut_pack_chunks() {
    constexpr std::uint32_t kGroups = std::max<std::uint32_t>(1, kPackChunk / W);
    pack_chunks_.clear();
    for (std::uint32_t c = 0; c < layout_.colors; ++c) {
      const std::vector<ContactRun>& runs = colors_[c].runs;
      for (std::uint32_t r = 0; r < runs.size(); ++r) {
        const std::uint32_t groups = runs[r].end - runs[r].begin;
        for (std::uint32_t k = 0; k < groups; k += kGroups) {
          pack_chunks_.push_back({c, r, k, std::min(k + kGroups, groups)});
        }
      }
    }
    next_pack_chunk_.store(0, std::memory_order_relaxed);
  }

  // The same slices as run_share's, so each thread clears the groups it then solves.
  template <int V>
  static void clear_share(ContactBatch<V>& batch, const solver::Share& share) {
    for (const ContactRun& r : batch.runs) {
      const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
      for (std::size_t k = slice.begin; k < slice.end; ++k) {
        simd::ContactLanes<V>& g = batch.groups[r.begin + k];
        for (auto& p : g.point) {
          std::fill(std::begin(p.normal_impulse), std::end(p.normal_impulse), 0.0f);
          for (auto& t : p.tangent_impulse) std::fill(std::begin(t), std::end(t), 0.0f);
        }
        for (auto& axis : g.rolling_impulse) std::fill(std::begin(axis), std::end(axis), 0.0f);
      }
    }
  }

  template <int V>
  void store_share(const ContactBatch<V>& batch, const solver::Share& share) {
    for (const ContactRun& r : batch.runs) {
      const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
      for (std::size_t k = slice.begin; k < slice.end; ++k) {
        const simd::ContactLanes<V>& g = batch.groups[r.begin + k];
        const std::size_t first = r.first_entry + k * V;
        for (int lane = 0; lane < V; ++lane) {
          if (g.id[lane] == kPadding) continue;  // padding lanes come last
          read_lane<V>(g, lane, packed_[first + lane], step_.next->slot_entry(first + lane));
        }
      }
    }
  }

  void fetch_for_packing(std::uint32_t index) const {
    const ContactManifold& m = step_.manifolds[index];
    prefetch_object(m);
    prefetch_object((*step_.bodies)[m.body_a.index].orientation);
    prefetch_object((*step_.bodies)[m.body_b.index].orientation);
  }

  template <int V>
  static void run_share(ContactBatch<V>& batch, const solver::ContactKernels<V>& kernels,
                        const solver::Share& share, ContactPass pass,
                        const simd::BodyArrays& arrays, const simd::SubstepContext& ctx,
                        const simd::ContactContext& cc, std::uint32_t signature_mask = ~0u) {
    for (const ContactRun& r : batch.runs) {
      const solver::Slice slice = solver::slice_of(r.end - r.begin, share);
      if (slice.end > slice.begin) {
        pass_of<V>(kernels, pass, r.signature & signature_mask)(
            batch.groups.data() + r.begin + slice.begin, slice.end - slice.begin, arrays, ctx, cc);
      }
    }
  }

  // As the joints: colour by colour with a barrier after each, then the overflow in order.
  void run_colors(const solver::Share& share, ContactPass pass, const simd::BodyArrays& arrays,
                  const simd::SubstepContext& ctx, const simd::ContactContext& cc,
                  std::uint32_t signature_mask = ~0u) {
    for (std::uint32_t c = 0; c < layout_.colors; ++c) {
      run_share<W>(colors_[c], kernels_, share, pass, arrays, ctx, cc, signature_mask);
      solver::team_barrier(share);
    }
    if (!overflow_.groups.empty()) {
      if (share.thread == 0)
        run_share<1>(overflow_, scalar_, solver::Share{}, pass, arrays, ctx, cc, signature_mask);
      solver::team_barrier(share);
    }
  }

  solver::ContactKernels<W> kernels_;
  solver::ContactKernels<1> scalar_;
  ContactLayout layout_;
  ContactStep step_;
  std::vector<Entry> unsorted_;  // the manifolds in lanes, in input order
  std::vector<Entry> entries_;   // sorted by order_key
  std::array<std::uint32_t, kOrderKeys> counts_{};
  std::vector<std::uint32_t> left_out_;  // manifolds not in lanes, in input order
  // What the last load that laid its manifolds out read, per manifold in input order, and
  // the bodies' version then (valid only after a load that returned true).
  std::vector<ContactLayoutInput> inputs_;
  std::uint64_t inputs_version_ = 0;
  bool inputs_valid_ = false;
  struct PackChunk {
    std::uint32_t color, run, begin, end;  // groups [begin, end) of colors_[color].runs[run]
  };
  std::vector<PackChunk> pack_chunks_;
  std::atomic<std::size_t> next_pack_chunk_{0};  // the next chunk a thread takes
  // Per entry, in the solver's order: written by whichever thread packs its chunk, read by
  // store's shares (the barriers between order them).
  PagedVector<PackedManifold> packed_;
  std::vector<std::uint32_t> body_colors_;  // per body slot, scratch of load (all zero between)
  std::uint64_t used_colors_ = 0;
  // The first layout_.colors are this step's; the rest keep their memory for later steps.
  std::vector<ContactBatch<W>> colors_;
  ContactBatch<1> overflow_;
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
