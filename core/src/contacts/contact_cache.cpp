#include "contacts/contact_cache.hpp"

#include <algorithm>
#include <tuple>

namespace softstep {

bool ContactCache::insert(const ContactPairKey& key, const CachedManifold& manifold) {
  if (entries_.empty()) index_.reset(0);
  const auto position = static_cast<std::uint32_t>(entries_.size());
  if (index_.insert(key, position) != ContactKeyIndex::kAbsent) return false;
  entries_.push_back({key, manifold});
  keys_.push_back(key);
  slot_of_.push_back(position);
  return true;
}

std::size_t ContactCache::index_step(std::span<const ContactManifold> manifolds,
                                     const ContactCache& previous) {
  bool unchanged = manifolds.size() == previous.size();
  for (std::size_t i = 0; unchanged && i < manifolds.size(); ++i) {
    unchanged = previous.same_key_at(i, manifolds[i]);
  }
  return index_step(manifolds, unchanged);
}

std::size_t ContactCache::index_step(std::span<const ContactManifold> manifolds, bool unchanged) {
  // A scene at rest hands the same manifolds in the same order step after step: their keys
  // are then the previous step's, which were unique, at the same positions, and so is the
  // index. They are taken over when the step stores this cache, not copied here: on the
  // pyramid's 14,950 manifolds the copy moved 1.4 MB (the table and the keys) on the caller's
  // thread while the step's other thread waited.
  index_is_previous_ = unchanged;
  if (unchanged) return kNoRepeat;
  index_.reset(manifolds.size());
  keys_.resize(manifolds.size());
  for (std::size_t i = 0; i < manifolds.size(); ++i) {
    keys_[i] = contact_pair_key(manifolds[i]);
    if (index_.insert(keys_[i], static_cast<std::uint32_t>(i)) != ContactKeyIndex::kAbsent) {
      return i;
    }
  }
  return kNoRepeat;
}

void ContactCache::become_current(ContactCache& current) {
  if (index_is_previous_) {
    index_.swap(current.index_);
    keys_.swap(current.keys_);
    index_is_previous_ = false;
  }
  std::swap(*this, current);
}

void ContactCache::erase_body(std::uint64_t body_word) {
  // Rebuilt in input order, each entry at its own position: the order insert() keeps.
  PagedVector<ContactCacheEntry> kept;
  kept.reserve(entries_.size());
  for (std::size_t position = 0; position < slot_of_.size(); ++position) {
    const ContactCacheEntry& e = at_position(position);
    if (e.key.low != body_word && e.key.high != body_word) kept.push_back(e);
  }
  entries_.swap(kept);
  keys_.resize(entries_.size());
  slot_of_.resize(entries_.size());
  index_.reset(entries_.size());
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    keys_[i] = entries_[i].key;
    slot_of_[i] = static_cast<std::uint32_t>(i);
    index_.insert(keys_[i], static_cast<std::uint32_t>(i));
  }
}

void read_out(const ContactCache& cache, std::vector<ContactReading>& readings) {
  const auto body = [](std::uint64_t word) {
    return BodyId{static_cast<std::uint32_t>(word), static_cast<std::uint32_t>(word >> 32)};
  };
  readings.resize(cache.size());
  for (std::size_t i = 0; i < cache.size(); ++i) {
    const ContactCacheEntry& e = cache.at_position(i);
    const CachedManifold& c = e.manifold;
    ContactReading& r = readings[i];
    r = ContactReading{};
    const bool a_is_low = static_cast<std::uint32_t>(e.key.low) == c.body_a;
    r.body_a = body(a_is_low ? e.key.low : e.key.high);
    r.body_b = body(a_is_low ? e.key.high : e.key.low);
    r.point_count = c.point_count;
    r.rolling_impulse = c.rolling_impulse;
    for (std::size_t k = 0; k < c.point_count; ++k) {
      r.points[k] = {c.normal_impulse[k], c.friction_impulse[k], c.max_normal_impulse[k],
                     ((c.new_points >> k) & 1u) != 0};
    }
  }
}

std::vector<const ContactCacheEntry*> sorted_entries(const ContactCache& cache) {
  std::vector<const ContactCacheEntry*> entries;
  entries.reserve(cache.size());
  for (const ContactCacheEntry& entry : cache.entries()) entries.push_back(&entry);
  std::sort(entries.begin(), entries.end(), [](const auto* x, const auto* y) {
    const ContactPairKey &a = x->key, &b = y->key;
    return std::tie(a.low, a.high, a.key) < std::tie(b.low, b.high, b.key);
  });
  return entries;
}

}  // namespace softstep
