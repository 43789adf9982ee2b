// The contacts' warm-start cache: what each manifold of a step left for the next step, found
// by its body pair and key. Flat: the entries in the order the step's solver met its manifolds
// (its lanes' order, then the manifolds it left out, in input order; after erase_body or a
// scene file's insert()s, in input order), the keys in input order,
// where each manifold's entry is (slot_of), and a ContactKeyIndex from the keys to their input
// positions. All keep their memory between steps.
// Why two orders: the solver packs and reads back its lanes colour by colour, which meets the
// manifolds' input positions at random. A scene that hands the same manifolds step after step
// is coloured the same way every step, so entries kept in the solver's order are read by the
// next step's packing and written by its read-back front to back, not a 232-byte entry at a
// random place each. The checks compare each manifold's key with last step's at the same
// input position: the keys' own array, in input order, keeps that a walk through 24-byte
// records.
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
  // In no order that means anything to a caller (see the top of the file).
  std::span<const ContactCacheEntry> entries() const { return entries_; }
  // The entry of the manifold at this input position of the step that wrote the cache (or
  // of the insert() at that count).
  const ContactCacheEntry& at_position(std::size_t position) const {
    return entries_[slot_of_[position]];
  }

  // The entry of this key, or nullptr. hint: the input position the key likely had (a
  // manifold's position in its step: scenes tend to hand their manifolds in the same order
  // every step), looked at before the index. The index's answer is checked too: an index that
  // fell out of step with the entries would otherwise hand a manifold another's impulses,
  // silently; the compare costs nothing where the hint hits, as it does every step of a scene
  // in a fixed order.
  const ContactCacheEntry* find(const ContactPairKey& key, std::size_t hint = ~std::size_t{0}) const {
    if (hint < slot_of_.size()) {
      const ContactCacheEntry& e = entries_[slot_of_[hint]];
      if (e.key == key) return &e;
    }
    const std::uint32_t at = index_.find(key);
    if (at >= slot_of_.size()) return nullptr;
    const ContactCacheEntry& e = entries_[slot_of_[at]];
    return e.key == key ? &e : nullptr;
  }

  // Adds an entry unless its key is there already (then false, nothing changed).
  bool insert(const ContactPairKey& key, const CachedManifold& manifold);

  // Drops the entries that name this body (BodyId as generation << 32 | slot); the others keep
  // their input order.
  void erase_body(std::uint64_t body_word);

  // A step writes its next cache in two parts. Its validation indexes the step's keys (the
  // value of each is its manifold's position) with index_step, which returns the first
  // position whose key repeats an earlier one's (or kNoRepeat); then, once the world may
  // change, the entries are sized to the step's manifolds, each manifold is given its slot
  // (place) and each entry is written at its slot (each by one thread). Until then the cache
  // is scratch.
  static constexpr std::size_t kNoRepeat = ~std::size_t{0};
  std::size_t index_step(std::span<const ContactManifold> manifolds, const ContactCache& previous);
  // The same when the caller has found out, as it checked the manifolds, whether their keys
  // are the previous step's at the same positions (`unchanged`: same_key_at for every
  // manifold and the same count; false when unsure). Unchanged keys are not copied: this
  // cache takes the previous one's index and keys over in become_current (until then its own
  // are stale), so `current` there must be the `previous` here.
  std::size_t index_step(std::span<const ContactManifold> manifolds, bool unchanged);
  // Makes this cache, the step's next one, `current`, and `current` this (scratch for the
  // next step): a swap, in which this takes over current's index and keys when index_step found
  // them unchanged.
  void become_current(ContactCache& current);
  bool same_key_at(std::size_t position, const ContactManifold& m) const {
    return position < keys_.size() && keys_[position] == contact_pair_key(m);
  }
  // Starts loading the key at this position (when there is one) ahead of same_key_at.
  // (Measured only together with folding the comparison into the checks' pass: 0.90 -> 0.53
  // ms, when the keys were read out of the 232-byte entries.)
  void prefetch_key(std::size_t position) const {
    if (position < keys_.size()) prefetch_line(&keys_[position]);
  }
  void size_for_step(std::size_t manifolds) {
    entries_.resize(manifolds);
    slot_of_.resize(manifolds);
  }
  void place(std::size_t position, std::uint32_t slot) { slot_of_[position] = slot; }
  ContactCacheEntry& slot_entry(std::size_t slot) { return entries_[slot]; }

 private:
  PagedVector<ContactCacheEntry> entries_;  // in the solver's order (see the top of the file)
  PagedVector<ContactPairKey> keys_;        // in input order
  std::vector<std::uint32_t> slot_of_;      // input position -> its entry in entries_
  ContactKeyIndex index_;                   // key -> input position
  bool index_is_previous_ = false;          // index_step found the keys unchanged
};

// The readings of the step that wrote this cache, its manifolds in input order, into
// `readings`, which keeps its memory.
void read_out(const ContactCache& cache, std::vector<ContactReading>& readings);

// The cache's entries in the order of their keys (body pair, then key): the entries' own order
// is the last step's solver's, and the state hash and scene files need one that depends on
// neither the input's order nor the solver's.
std::vector<const ContactCacheEntry*> sorted_entries(const ContactCache& cache);

}  // namespace softstep
