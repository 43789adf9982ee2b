#include "contacts/contact_cache.hpp"

#include <algorithm>
#include <tuple>

namespace softstep {

bool ContactCache::insert(const ContactPairKey& key, const CachedManifold& manifold) {
  if (entries_.empty()) index_.reset(0);
  if (index_.insert(key, static_cast<std::uint32_t>(entries_.size())) !=
      ContactKeyIndex::kAbsent) {
    return false;
  }
  entries_.push_back({key, manifold});
  return true;
}

std::size_t ContactCache::index_step(std::span<const ContactManifold> manifolds,
                                     const ContactCache& previous) {
  bool unchanged = manifolds.size() == previous.size();
  for (std::size_t i = 0; unchanged && i < manifolds.size(); ++i) {
    unchanged = previous.same_key_at(i, manifolds[i]);
  }
  return index_step(manifolds, previous, unchanged);
}

std::size_t ContactCache::index_step(std::span<const ContactManifold> manifolds,
                                     const ContactCache& previous, bool unchanged) {
  // A scene at rest hands the same manifolds in the same order step after step: their keys
  // are then the previous step's, which were unique, at the same positions, and so is the index.
  if (unchanged) {
    index_ = previous.index_;  // the same size: a copy into the memory it has
    return kNoRepeat;
  }
  index_.reset(manifolds.size());
  for (std::size_t i = 0; i < manifolds.size(); ++i) {
    if (index_.insert(contact_pair_key(manifolds[i]), static_cast<std::uint32_t>(i)) !=
        ContactKeyIndex::kAbsent) {
      return i;
    }
  }
  return kNoRepeat;
}

void ContactCache::erase_body(std::uint64_t body_word) {
  std::erase_if(entries_, [body_word](const ContactCacheEntry& e) {
    return e.key.low == body_word || e.key.high == body_word;
  });
  index_.reset(entries_.size());
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    index_.insert(entries_[i].key, static_cast<std::uint32_t>(i));
  }
}

void read_out(const ContactCache& cache, std::vector<ContactReading>& readings) {
  const auto body = [](std::uint64_t word) {
    return BodyId{static_cast<std::uint32_t>(word), static_cast<std::uint32_t>(word >> 32)};
  };
  readings.resize(cache.size());
  for (std::size_t i = 0; i < cache.size(); ++i) {
    const ContactCacheEntry& e = cache.entries()[i];
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
