// The contacts' flat warm-start cache (core/src/contacts/contact_cache.hpp) and its key index,
// against std::unordered_map as the reference: the same answers for random keys (with
// repeats), for keys that all land on the same slot of a small table (linear probing around
// its end), and through growth.
#include <gtest/gtest.h>

#include <random>
#include <unordered_map>
#include <vector>

#include "contacts/contact_cache.hpp"

namespace softstep {
namespace {

ContactPairKey random_key(std::mt19937_64& rng, std::uint64_t range) {
  // Small ranges make repeats likely, so "already there" is exercised as much as "new".
  std::uniform_int_distribution<std::uint64_t> word(0, range);
  return {word(rng), word(rng), word(rng) % 3};
}

std::size_t home_slot(const ContactPairKey& k, std::size_t table) {
  return ContactPairHash{}(k) & (table - 1);
}

TEST(ContactKeyIndex, AnswersAsAMapForRandomKeysThroughGrowth) {
  std::mt19937_64 rng(7);
  ContactKeyIndex index;
  index.reset(0);  // the smallest table: it must grow many times below
  std::unordered_map<ContactPairKey, std::uint32_t, ContactPairHash> reference;
  for (std::uint32_t value = 0; value < 3000; ++value) {
    const ContactPairKey k = random_key(rng, 40);
    const auto it = reference.find(k);
    const std::uint32_t held = index.insert(k, value);
    if (it == reference.end()) {
      EXPECT_EQ(held, ContactKeyIndex::kAbsent);
      reference.emplace(k, value);
    } else {
      EXPECT_EQ(held, it->second) << "an insert of a present key returns what it holds";
    }
  }
  EXPECT_EQ(index.size(), reference.size());
  ASSERT_GT(reference.size(), 1000u);  // the growth above happened
  for (const auto& [k, v] : reference) EXPECT_EQ(index.find(k), v);
  for (int i = 0; i < 2000; ++i) {
    const ContactPairKey k = random_key(rng, 80);
    const auto it = reference.find(k);
    EXPECT_EQ(index.find(k), it == reference.end() ? ContactKeyIndex::kAbsent : it->second);
  }
}

TEST(ContactKeyIndex, KeysOnOneSlotProbePastTheTableEnd) {
  constexpr std::size_t kTable = ContactKeyIndex::kSmallestTable;
  // Keys whose home is the table's last slot: each next one must wrap to the front.
  std::mt19937_64 rng(11);
  std::vector<ContactPairKey> same_home;
  while (same_home.size() < kTable / 2) {
    const ContactPairKey k = random_key(rng, 1u << 30);
    if (home_slot(k, kTable) == kTable - 1) same_home.push_back(k);
  }
  ContactKeyIndex index;
  index.reset(same_home.size());  // at most half full: no growth, the table stays kTable
  for (std::uint32_t i = 0; i < same_home.size(); ++i) {
    EXPECT_EQ(index.insert(same_home[i], i), ContactKeyIndex::kAbsent);
  }
  for (std::uint32_t i = 0; i < same_home.size(); ++i) {
    EXPECT_EQ(index.find(same_home[i]), i);
    EXPECT_EQ(index.insert(same_home[i], 99), i);
  }
  // An absent key of the same home walks the whole run and stops at the first free slot.
  ContactPairKey absent{};
  do {
    absent = random_key(rng, 1u << 30);
  } while (home_slot(absent, kTable) != kTable - 1);
  EXPECT_EQ(index.find(absent), ContactKeyIndex::kAbsent);
  // reset empties it.
  index.reset(same_home.size());
  EXPECT_EQ(index.find(same_home[0]), ContactKeyIndex::kAbsent);
  EXPECT_EQ(index.size(), 0u);
}

ContactManifold manifold(std::uint32_t a, std::uint32_t b, std::uint64_t key) {
  ContactManifold m;
  m.body_a = {a, 1};
  m.body_b = {b, 1};
  m.key = key;
  return m;
}

TEST(ContactCache, StepIndexFindsTheFirstRepeatWhetherTakenOverOrRebuilt) {
  // The pair is unordered: (1, 2) and (2, 1) with the same key are the same manifold.
  const std::vector<ContactManifold> step = {manifold(1, 2, 0), manifold(3, 4, 0),
                                             manifold(2, 1, 1), manifold(2, 1, 0)};
  ContactCache empty, next;
  EXPECT_EQ(next.index_step(step, empty), 3u);
  const std::vector<ContactManifold> unique(step.begin(), step.end() - 1);
  EXPECT_EQ(next.index_step(unique, empty), ContactCache::kNoRepeat);
  // Each manifold's entry in a slot of its own, not at its input position (as the solver
  // writes them: in its order).
  const auto slot_of = [&](std::size_t position) {
    return static_cast<std::uint32_t>(unique.size() - 1 - position);
  };
  next.size_for_step(unique.size());
  for (std::size_t i = 0; i < unique.size(); ++i) {
    next.place(i, slot_of(i));
    next.slot_entry(slot_of(i)).key = contact_pair_key(unique[i]);
    next.slot_entry(slot_of(i)).manifold.point_count = static_cast<std::uint16_t>(i + 1);
  }
  // The same manifolds in the same order: the index is taken over from the cache it replaces
  // (become_current); in another order: rebuilt. Either way every key finds its manifold's
  // position, without a hint and with a wrong one.
  ContactCache copied, rebuilt;
  EXPECT_EQ(copied.index_step(unique, next), ContactCache::kNoRepeat);
  const std::vector<ContactManifold> reordered = {unique[2], unique[0], unique[1]};
  EXPECT_EQ(rebuilt.index_step(reordered, next), ContactCache::kNoRepeat);
  const std::vector<ContactManifold> with_repeat = {unique[2], unique[0], unique[2]};
  ContactCache repeated;
  EXPECT_EQ(repeated.index_step(with_repeat, next), 2u) << "a step unlike the last one";
  copied.size_for_step(unique.size());
  rebuilt.size_for_step(reordered.size());
  for (std::size_t i = 0; i < unique.size(); ++i) {
    copied.place(i, static_cast<std::uint32_t>(i));
    copied.slot_entry(i).key = contact_pair_key(unique[i]);
    rebuilt.place(i, static_cast<std::uint32_t>(i));
    rebuilt.slot_entry(i).key = contact_pair_key(reordered[i]);
  }
  ContactCache current = next;  // as the world's cache, which becomes the scratch
  copied.become_current(current);
  EXPECT_EQ(copied.size(), next.size()) << "the scratch: what was current";
  for (std::size_t i = 0; i < unique.size(); ++i) {
    const ContactPairKey k = contact_pair_key(unique[i]);
    ASSERT_NE(next.find(k), nullptr);
    EXPECT_EQ(next.find(k)->manifold.point_count, static_cast<int>(i) + 1);
    EXPECT_EQ(next.find(k, i), next.find(k)) << "the right hint";
    EXPECT_EQ(next.find(k, (i + 1) % unique.size()), next.find(k))
        << "a wrong hint falls back to the index";
    EXPECT_EQ(&next.at_position(i), next.find(k));
    EXPECT_TRUE(next.same_key_at(i, unique[i]));
    EXPECT_FALSE(next.same_key_at(i, unique[(i + 1) % unique.size()]));
    EXPECT_EQ(current.find(k), &current.entries()[i]);
    EXPECT_EQ(current.find(k, (i + 1) % unique.size()), &current.entries()[i]) << "the index";
    EXPECT_TRUE(current.same_key_at(i, unique[i]));
    ASSERT_NE(rebuilt.find(k), nullptr);
    EXPECT_EQ(rebuilt.find(k)->key, k);
  }
  EXPECT_EQ(next.find(contact_pair_key(manifold(1, 3, 0))), nullptr);
}

TEST(ContactCache, InsertRefusesARepeatAndErasingABodyKeepsTheRestFound) {
  ContactCache cache;
  CachedManifold c;
  for (std::uint32_t body = 1; body <= 6; ++body) {
    c.point_count = static_cast<std::uint16_t>(body);
    EXPECT_TRUE(cache.insert(contact_pair_key(manifold(body, body + 1, 0)), c));
  }
  EXPECT_FALSE(cache.insert(contact_pair_key(manifold(2, 1, 0)), c)) << "(1, 2) is there";
  const std::uint64_t body_3 = (std::uint64_t{1} << 32) | 3u;
  cache.erase_body(body_3);  // (2, 3) and (3, 4) go
  EXPECT_EQ(cache.size(), 4u);
  EXPECT_EQ(cache.find(contact_pair_key(manifold(2, 3, 0))), nullptr);
  EXPECT_EQ(cache.find(contact_pair_key(manifold(3, 4, 0))), nullptr);
  for (std::uint32_t body : {1u, 4u, 5u, 6u}) {
    const ContactCacheEntry* e = cache.find(contact_pair_key(manifold(body, body + 1, 0)));
    ASSERT_NE(e, nullptr) << body;
    EXPECT_EQ(e->manifold.point_count, static_cast<int>(body));
  }
}

TEST(ContactCache, ErasingABodyKeepsTheOthersInInputOrderWhateverTheirSlots) {
  // A step's cache: three manifolds whose entries sit in the reverse of their input order.
  const std::vector<ContactManifold> step = {manifold(1, 2, 0), manifold(3, 4, 0),
                                             manifold(5, 6, 0)};
  ContactCache empty, cache;
  ASSERT_EQ(cache.index_step(step, empty), ContactCache::kNoRepeat);
  cache.size_for_step(step.size());
  for (std::size_t i = 0; i < step.size(); ++i) {
    const auto slot = static_cast<std::uint32_t>(step.size() - 1 - i);
    cache.place(i, slot);
    cache.slot_entry(slot).key = contact_pair_key(step[i]);
  }
  cache.erase_body((std::uint64_t{1} << 32) | 4u);  // (3, 4) goes
  ASSERT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.at_position(0).key, contact_pair_key(step[0]));
  EXPECT_EQ(cache.at_position(1).key, contact_pair_key(step[2]));
  EXPECT_TRUE(cache.same_key_at(1, step[2])) << "the keys' own array follows";
  EXPECT_EQ(cache.find(contact_pair_key(step[2]), 1), &cache.at_position(1));
}

}  // namespace
}  // namespace softstep
