// The step's contacts in lanes, beside the joints (DESIGN.md terms: a second set of coloured
// batches). Contacts come and go every step, so they are coloured and packed every step on
// their own: their churn never re-packs, re-colours or re-plans the joints. Within each pass
// the joints' colours run first, then the contacts' colours (each colour followed by a
// barrier), then the contacts that found no colour, in input order on thread 0.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "softstep/contacts.hpp"
#include "softstep/simd/contact_kernel.hpp"
#include "softstep/world_settings.hpp"
#include "solver/joint_batches.hpp"

namespace softstep {

struct BodySlot;

// What a manifold left for the next step's warm start, keyed by its ordered body pair and key.
struct CachedManifold {
  std::uint32_t body_a = 0;  // the slot that was A (impulses on B flip sign when A and B swap)
  int point_count = 0;
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

struct ContactPairKey {
  std::uint64_t low, high;  // (generation << 32 | slot) of the lower and the higher slot
  std::uint64_t key;
  bool operator==(const ContactPairKey&) const = default;
};
struct ContactPairHash {
  std::size_t operator()(const ContactPairKey& k) const noexcept;
};
using ContactCache = std::unordered_map<ContactPairKey, CachedManifold, ContactPairHash>;

ContactPairKey contact_pair_key(const ContactManifold& m);
// The cache's entries in the order of their keys (body pair, then key): the map's own order
// depends on its history, and the state hash and scene files need one that does not.
std::vector<const ContactCache::value_type*> sorted_entries(const ContactCache& cache);

// How the step's contacts were laid out (for the plan and the profile).
struct ContactLayout {
  std::uint32_t manifolds = 0;  // in lanes this step (both ends static or asleep: left out)
  std::uint32_t points = 0;
  std::uint32_t colors = 0;
  std::uint32_t overflow = 0;  // manifolds solved in order on one thread
  std::uint32_t signatures = 0;  // union of the manifolds' ContactFeature bits
  bool restitution = false;      // some manifold asks for restitution
  double load_ms = 0.0;          // matching, colouring and packing, this step
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  // Serial, before the step's threads start: matches the manifolds with the cache (warm
  // start), colours and packs them. Manifolds whose bodies are all static or asleep are left
  // out; their cache entries carry over.
  virtual void load(std::span<const ContactManifold> manifolds,
                    const std::vector<BodySlot>& bodies, const ContactCache& cache,
                    bool warm_start) = 0;
  virtual const ContactLayout& layout() const = 0;
  bool empty() const { return layout().manifolds == 0; }
  // Each thread its share; prepare ends without a barrier, the others with one per colour.
  virtual void prepare(const simd::BodyArrays&, const simd::SubstepContext&,
                       const solver::Share&) = 0;
  virtual void warm_start(const simd::BodyArrays&, const simd::SubstepContext&,
                          const simd::ContactContext&, const solver::Share&) = 0;
  virtual void solve(const simd::BodyArrays&, const simd::SubstepContext&,
                     const simd::ContactContext&, const solver::Share&) = 0;
  virtual void relax(const simd::BodyArrays&, const simd::SubstepContext&,
                     const simd::ContactContext&, const solver::Share&) = 0;
  virtual void restitute(const simd::BodyArrays&, const simd::SubstepContext&,
                         const simd::ContactContext&, const solver::Share&) = 0;
  // Serial, after the step: the readings in input order and the cache for the next step.
  virtual void store(std::span<const ContactManifold> manifolds, const ContactCache& previous,
                     ContactCache& next, std::vector<ContactReading>& readings) const = 0;
};

std::unique_ptr<ContactSolver> make_contact_solver(SimdWidth width);

// The contact spring of one sub-step h.
simd::ContactContext make_contact_context(const ContactSettings& settings, float h);

}  // namespace softstep
