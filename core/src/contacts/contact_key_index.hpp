// A manifold's identity across steps (its body pair and key), and a flat index from such keys
// to positions: an open-addressing table (power-of-two size, linear probing, at most half
// full). The step's validation fills it to find repeated keys, and the same table then indexes
// the next warm-start cache by the manifolds' input positions (contact_cache.hpp); the next
// step looks its manifolds up in it. No node per key, and its memory is kept between steps.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace softstep {

struct ContactPairKey {
  std::uint64_t low, high;  // the pair's two (generation << 32 | slot) words, the smaller first
  std::uint64_t key;
  bool operator==(const ContactPairKey&) const = default;
};

struct ContactPairHash {
  std::size_t operator()(const ContactPairKey& k) const noexcept {
    // splitmix64-style mixing of the three words; any fixed function keeps lookups
    // deterministic (no order that matters ever comes from the table).
    std::uint64_t h = k.low * 0x9E3779B97F4A7C15ull;
    h ^= (k.high + 0xBF58476D1CE4E5B9ull + (h << 6) + (h >> 2));
    h ^= (k.key + 0x94D049BB133111EBull + (h << 6) + (h >> 2));
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

class ContactKeyIndex {
 public:
  static constexpr std::uint32_t kAbsent = ~0u;
  static constexpr std::size_t kSmallestTable = 16;

  // Empties the index, sized for `count` keys (it grows if more come). The table's memory is
  // reused when the size is unchanged, as it is from one step of a scene to the next.
  void reset(std::size_t count) {
    const std::size_t size = std::bit_ceil(std::max(kSmallestTable, 2 * count));
    if (slots_.size() == size) {
      std::fill(slots_.begin(), slots_.end(), Slot{});
    } else {
      slots_.assign(size, Slot{});
    }
    count_ = 0;
  }

  std::size_t size() const { return count_; }
  void swap(ContactKeyIndex& other) noexcept {
    slots_.swap(other.slots_);
    std::swap(count_, other.count_);
  }

  // The value held for the key, or kAbsent.
  std::uint32_t find(const ContactPairKey& key) const {
    if (slots_.empty()) return kAbsent;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = ContactPairHash{}(key) & mask;; i = (i + 1) & mask) {
      const Slot& s = slots_[i];
      if (s.value == kAbsent) return kAbsent;
      if (s.key == key) return s.value;
    }
  }

  // Holds value for the key unless the key is there already: then returns the value held
  // and changes nothing; otherwise kAbsent. (value must not be kAbsent.)
  std::uint32_t insert(const ContactPairKey& key, std::uint32_t value) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = ContactPairHash{}(key) & mask;; i = (i + 1) & mask) {
      Slot& s = slots_[i];
      if (s.value == kAbsent) {
        s = {key, value};
        ++count_;
        return kAbsent;
      }
      if (s.key == key) return s.value;
    }
  }

 private:
  struct Slot {
    ContactPairKey key{0, 0, 0};
    std::uint32_t value = kAbsent;
  };

  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max(kSmallestTable, 2 * old.size()), Slot{});
    count_ = 0;
    for (const Slot& s : old) {
      if (s.value != kAbsent) insert(s.key, s.value);
    }
  }

  std::vector<Slot> slots_;
  std::size_t count_ = 0;
};

}  // namespace softstep
