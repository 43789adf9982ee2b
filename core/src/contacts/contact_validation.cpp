#include "contacts/contact_validation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contacts/contact_cache.hpp"
#include "prefetch.hpp"
#include "validation.hpp"

namespace softstep::validation {

namespace {

// The normal must be nearly unit (a direction, not a force); the packing makes it exactly unit
// for the kernels' frame (contact_solver.cpp, unit_normal).
constexpr double kUnitTolerance = 1e-4;

std::string bounded(std::string_view rule, double low, double high) {
  return std::string(rule) + " in [" + format(low) + ", " + format(high) + "]";
}

void in_range(std::string_view call, const std::string& field, double value, double low,
              double high) {
  finite(call, field, value);
  if (value < low || value > high) reject(call, field, format(value), bounded("must be", low, high));
}

bool body_alive(const World::Impl& w, BodyId id) {
  return id.index < w.bodies.size() && w.bodies[id.index].alive &&
         w.bodies[id.index].generation == id.generation;
}

// Starts loading the lines body_alive reads for this manifold: the body slots are 424 bytes
// apart, met in the manifolds' order, and their test was a quarter of the checks' samples.
void prefetch_bodies(const World::Impl& w, const ContactManifold& m) {
  if (m.body_a.index < w.bodies.size()) prefetch_line(&w.bodies[m.body_a.index]);
  if (m.body_b.index < w.bodies.size()) prefetch_line(&w.bodies[m.body_b.index]);
}

// NaN fails both comparisons and the bounds are finite, so no finiteness test is needed.
bool within(double value, double low, double high) {
  return (value >= low) & (value <= high);
}

// The rules of describe_failure as plain comparisons, without text: a step's manifolds are
// valid in practice, and naming each field up front (a string per field and point) cost more
// than matching and packing the contacts (the 820-box pyramid: about half of step()).
bool passes(const World::Impl& w, const ContactManifold& m) {
  if (!body_alive(w, m.body_a) || !body_alive(w, m.body_b) || m.body_a.index == m.body_b.index)
    return false;
  if (m.point_count < 1 || m.point_count > kMaxContactPoints) return false;
  // The field rules joined with &= rather than ||: they all hold in practice, and one test of
  // the whole is cheaper than a branch per field.
  bool fields = in_envelope(m.normal);
  fields &= std::abs(m.normal.norm() - 1.0) <= kUnitTolerance;
  fields &= within(m.friction, 0.0, kMaxMagnitude);
  fields &= within(m.restitution, 0.0, 1.0);
  fields &= within(m.rolling_resistance, 0.0, kMaxMagnitude);
  fields &= within(m.tangent_speed.x(), -kMaxMagnitude, kMaxMagnitude);
  fields &= within(m.tangent_speed.y(), -kMaxMagnitude, kMaxMagnitude);
  fields &= within(m.radius_a, 0.0, kMaxMagnitude);
  fields &= within(m.radius_b, 0.0, kMaxMagnitude);
  if (!fields) return false;
  for (int k = 0; k < m.point_count; ++k) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    bool point = in_envelope(p.anchor_a);
    point &= in_envelope(p.anchor_b);
    point &= within(p.separation, -kMaxMagnitude, kMaxMagnitude);
    if (!point) return false;
    for (int earlier = 0; earlier < k; ++earlier) {
      if (m.points[static_cast<std::size_t>(earlier)].feature_id == p.feature_id) return false;
    }
  }
  return true;
}

// Rejects manifold i naming the first field that breaks a rule.
[[noreturn]] void describe_failure(std::string_view call, const World::Impl& w,
                                   const ContactManifold& m, std::size_t i) {
  const std::string at = "contacts[" + std::to_string(i) + "]";
  const std::uint32_t a = body_slot(w, call, at + ".body_a", m.body_a);
  const std::uint32_t b = body_slot(w, call, at + ".body_b", m.body_b);
  if (a == b) {
    reject(call, at + ".body_b", "BodyId{" + std::to_string(b) + "}",
           "a body cannot touch itself (body_a == body_b)");
  }
  finite(call, at + ".normal", m.normal);
  if (std::abs(m.normal.norm() - 1.0) > kUnitTolerance) {
    reject(call, at + ".normal", format(m.normal), "must be a unit vector (from A to B)");
  }
  if (m.point_count < 1 || m.point_count > kMaxContactPoints) {
    reject(call, at + ".point_count", std::to_string(m.point_count),
           "must be in [1, " + std::to_string(kMaxContactPoints) + "]");
  }
  in_range(call, at + ".friction", m.friction, 0.0, kMaxMagnitude);
  in_range(call, at + ".restitution", m.restitution, 0.0, 1.0);
  in_range(call, at + ".rolling_resistance", m.rolling_resistance, 0.0, kMaxMagnitude);
  in_range(call, at + ".tangent_speed.x", m.tangent_speed.x(), -kMaxMagnitude, kMaxMagnitude);
  in_range(call, at + ".tangent_speed.y", m.tangent_speed.y(), -kMaxMagnitude, kMaxMagnitude);
  in_range(call, at + ".radius_a", m.radius_a, 0.0, kMaxMagnitude);
  in_range(call, at + ".radius_b", m.radius_b, 0.0, kMaxMagnitude);
  for (int k = 0; k < m.point_count; ++k) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    const std::string pt = at + ".points[" + std::to_string(k) + "]";
    finite(call, pt + ".anchor_a", p.anchor_a);
    finite(call, pt + ".anchor_b", p.anchor_b);
    in_range(call, pt + ".separation", p.separation, -kMaxMagnitude, kMaxMagnitude);
    for (int earlier = 0; earlier < k; ++earlier) {
      if (m.points[static_cast<std::size_t>(earlier)].feature_id == p.feature_id) {
        reject(call, pt + ".feature_id", std::to_string(p.feature_id),
               "repeats points[" + std::to_string(earlier) +
                   "]'s: feature ids tell a manifold's points apart");
      }
    }
  }
  throw std::logic_error("contact validation: passes() and describe_failure() disagree on " + at);
}

}  // namespace

ContactChecks::ContactChecks(const World::Impl& world, std::span<const ContactManifold> manifolds,
                             const ContactLayoutInput* last_layout)
    : world_(world),
      manifolds_(manifolds),
      unchanged_(manifolds.size() == world.contact_cache.size()),
      last_layout_(last_layout),
      same_layout_(last_layout != nullptr) {}

void ContactChecks::scan() {
  // One pass over the manifolds checks the rules and whether the keys are last step's at the
  // same positions (then the index is last step's too), fetching last step's keys ahead. On
  // the 5,050-box pyramid's 14,950 manifolds: 0.53 ms, against 0.90 ms as two passes (keys,
  // then rules; medians of 5 alternated runs, 2026-11-26).
  const ContactCache& previous = world_.contact_cache;
  for (;;) {
    const std::size_t chunk = next_chunk_.fetch_add(1, std::memory_order_relaxed);
    const std::size_t begin = chunk * kChunk;
    if (begin >= manifolds_.size()) return;
    const std::size_t end = std::min(manifolds_.size(), begin + kChunk);
    bool same = unchanged_.load(std::memory_order_relaxed);
    bool same_layout = same_layout_.load(std::memory_order_relaxed);
    for (std::size_t i = begin; i < end; ++i) {
      const ContactManifold& m = manifolds_[i];
      constexpr std::size_t kAhead = 8;  // manifolds
      if (i + kAhead < end) prefetch_bodies(world_, manifolds_[i + kAhead]);
      if (same) {
        previous.prefetch_key(i + kAhead);
        same = previous.same_key_at(i, m);
      }
      // Read while the checks have the manifold's lines: the pass the layout would make.
      if (same_layout) same_layout = contact_layout_input(m) == last_layout_[i];
      if (!passes(world_, m)) {
        // The keys after it in this chunk were not compared: unsure, so finish indexes them.
        same = false;
        same_layout = false;
        std::size_t first = failure_.load(std::memory_order_relaxed);
        while (i < first && !failure_.compare_exchange_weak(first, i, std::memory_order_relaxed)) {
        }
        break;
      }
    }
    if (!same) unchanged_.store(false, std::memory_order_relaxed);
    if (!same_layout) same_layout_.store(false, std::memory_order_relaxed);
  }
}

void ContactChecks::finish(std::string_view call, ContactCache& next) const {
  // Keys only read ids, so they are safe to index before the fields are checked; errors are
  // still reported for the first manifold in input order that breaks any rule (a manifold
  // that breaks a rule and repeats a key is named for the rule). After a broken manifold the
  // keys are indexed whole (unchanged_ is false), and the index it leaves is scratch.
  const std::size_t failure = failure_.load(std::memory_order_relaxed);
  const std::size_t repeat =
      next.index_step(manifolds_, unchanged_.load(std::memory_order_relaxed));
  if (failure != kNone && failure <= repeat) {
    describe_failure(call, world_, manifolds_[failure], failure);
  }
  if (repeat != ContactCache::kNoRepeat) {
    reject(call, "contacts[" + std::to_string(repeat) + "].key",
           std::to_string(manifolds_[repeat].key),
           "another manifold of this step has the same body pair and key");
  }
}

}  // namespace softstep::validation
