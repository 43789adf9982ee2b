// The contacts' warm-start cache: what each manifold of a step left for the next step, found
// by its body pair and key. Flat: the entries are the step's manifolds in input order, beside
// a ContactKeyIndex from their keys to their positions. Both keep their memory between steps.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "contacts/contact_key_index.hpp"
#include "paged_vector.hpp"
#include "prefetch.hpp"
#include "softstep/contacts.hpp"

namespace softstep {

// What a manifold left for the next step's warm start, keyed by its ordered body pair and key.
struct CachedManifold {
  std::uint32_t body_a = 0;  // the slot that was A (impulses on B flip sign when A and B swap)
  std::uint16_t point_count = 0;
  // Bit i: point i had no twin in the step before (ContactPointReading::is_new). Not part of
  // the warm-start state: no scene file or state hash holds it.
  std::uint16_t new_points = 0;
  std::array<std::uint32_t, kMaxContactPoints> feature_id{};
  std::array<double, kMaxContactPoints> normal_impulse{};
  // on B, world; zeros spelt out: {} leaves an Eigen vector uninitialized (gcc under ASan
  // rightly warns that moving such a manifold reads them)
  std::array<Eigen::Vector3d, kMaxContactPoints> friction_impulse{
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
      Eigen::Vector3d::Zero()};
  static_assert(kMaxContactPoints == 4, "one Zero() per point above");
  std::array<double, kMaxContactPoints> max_normal_impulse{};
  Eigen::Vector3d rolling_impulse = Eigen::Vector3d::Zero();  // on B, world
};

struct ContactCacheEntry {
  ContactPairKey key;
  CachedManifold manifold;
};

// A body id as one word, generation << 32 | slot, as the contact keys hold it.
inline std::uint64_t body_word(BodyId id) {
  return (std::uint64_t(id.generation) << 32) | std::uint64_t(id.index);
}

// Inline: the step's validation compares every manifold's key with last step's.
inline ContactPairKey contact_pair_key(const ContactManifold& m) {
  const std::uint64_t a = body_word(m.body_a), b = body_word(m.body_b);
  return {std::min(a, b), std::max(a, b), m.key};
}

class ContactCache {
 public:
  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  std::span<const ContactCacheEntry> entries() const { return entries_; }

  // The entry of this key, or nullptr. hint: where the key likely is (a manifold's position in
  // its step: scenes tend to hand their manifolds in the same order every step), looked at
  // before the index. The index's answer is checked too: an index that fell out of step with
  // the entries would otherwise hand a manifold another's impulses, silently; the compare
  // costs nothing where the hint hits, as it does every step of a scene in a fixed order.
  const ContactCacheEntry* find(const ContactPairKey& key, std::size_t hint = ~std::size_t{0}) const {
    if (hint < entries_.size() && entries_[hint].key == key) return &entries_[hint];
    const std::uint32_t at = index_.find(key);
    if (at >= entries_.size() || !(entries_[at].key == key)) return nullptr;
    return &entries_[at];
  }

  // Adds an entry unless its key is there already (then false, nothing changed).
  bool insert(const ContactPairKey& key, const CachedManifold& manifold);

  // Drops the entries that name this body (BodyId as generation << 32 | slot).
  void erase_body(std::uint64_t body_word);

  // A step writes its next cache in two parts. Its validation indexes the step's keys (the
  // value of each is its manifold's position) with index_step, which returns the first
  // position whose key repeats an earlier one's (or kNoRepeat); then, once the world may
  // change, the entries are sized to the step's manifolds and each entry is written at its
  // manifold's position (each by one thread). Until then the cache is scratch.
  static constexpr std::size_t kNoRepeat = ~std::size_t{0};
  std::size_t index_step(std::span<const ContactManifold> manifolds, const ContactCache& previous);
  // The same when the caller has found out, as it checked the manifolds, whether their keys
  // are the previous step's at the same positions (`unchanged`: same_key_at for every
  // manifold and the same count; false when unsure).
  std::size_t index_step(std::span<const ContactManifold> manifolds, const ContactCache& previous,
                         bool unchanged);
  bool same_key_at(std::size_t position, const ContactManifold& m) const {
    return position < entries_.size() && entries_[position].key == contact_pair_key(m);
  }
  // Starts loading the entry at this position (when there is one) ahead of same_key_at: the
  // entries are 232 bytes apart, and each comparison reads one line of them. (Measured only
  // together with folding the comparison into the checks' pass: 0.90 -> 0.53 ms.)
  void prefetch_key(std::size_t position) const {
    if (position < entries_.size()) prefetch_line(&entries_[position].key);
  }
  void size_for_step(std::size_t manifolds) { entries_.resize(manifolds); }
  ContactCacheEntry& step_entry(std::size_t manifold) { return entries_[manifold]; }

 private:
  PagedVector<ContactCacheEntry> entries_;
  ContactKeyIndex index_;  // key -> position in entries_
};

// The readings of the step that wrote this cache (its entries are that step's manifolds in
// input order), into `readings`, which keeps its memory.
void read_out(const ContactCache& cache, std::vector<ContactReading>& readings);

// The cache's entries in the order of their keys (body pair, then key): the entries' own order
// is the last step's input order, and the state hash and scene files need one that is not.
std::vector<const ContactCacheEntry*> sorted_entries(const ContactCache& cache);

}  // namespace softstep
