// The step's contacts in lanes, beside the joints (DESIGN.md terms: a second set of coloured
// batches). Contacts come and go every step, so they are coloured and packed every step on
// their own: their churn never re-packs, re-colours or re-plans the joints. Within each pass
// the joints' colours run first, then the contacts' colours (each colour followed by a
// barrier), then the contacts that found no colour, in input order on thread 0.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "contacts/contact_cache.hpp"
#include "slot_vectors.hpp"
#include "softstep/contacts.hpp"
#include "softstep/simd/contact_kernel.hpp"
#include "softstep/world_settings.hpp"
#include "solver/joint_batches.hpp"

namespace softstep {

// The step's contacts and where their results go, handed to load; held until store returns.
struct ContactStep {
  std::span<const ContactManifold> manifolds;
  const BodySlots* bodies = nullptr;
  const ContactCache* previous = nullptr;  // the last step's warm-start cache
  ContactCache* next = nullptr;  // indexed by the step's validation (ContactCache::index_step)
  bool warm_start = true;
  // Changes whenever a body's slot, type or sleep changes (World::Impl::bodies_version).
  std::uint64_t bodies_version = 0;
};

// What the layout reads of a manifold besides its bodies' states (awake, dynamic): its
// bodies' slots, its point count and which rows and passes it asks for. The checks compare
// it with the last layout's as they read each manifold (contact_validation.hpp).
struct ContactLayoutInput {
  std::uint32_t body_a, body_b, shape;
  bool operator==(const ContactLayoutInput&) const = default;
};
inline ContactLayoutInput contact_layout_input(const ContactManifold& m) {
  const auto flag = [](bool on, int bit) { return static_cast<std::uint32_t>(on) << bit; };
  return {m.body_a.index, m.body_b.index,
          static_cast<std::uint32_t>(m.point_count) | flag(m.friction > 0.0, 8) |
              flag(m.rolling_resistance > 0.0, 9) | flag(m.restitution > 0.0, 10)};
}

// How the step's contacts were laid out (for the plan and the profile).
struct ContactLayout {
  std::uint32_t manifolds = 0;  // in lanes this step (both ends static or asleep: left out)
  std::uint32_t points = 0;
  std::uint32_t colors = 0;
  std::uint32_t overflow = 0;  // manifolds solved in order on one thread
  std::uint32_t signatures = 0;  // union of the manifolds' ContactFeature bits
  bool restitution = false;      // some manifold asks for restitution
  double load_ms = 0.0;          // this step's load (colouring and sorting)
  bool same_inputs = false;      // the layout before this one had the same inputs
  bool kept = false;             // and this load kept it without colouring again
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  // One thread, before the step's stages: colours the manifolds, orders them by colour,
  // signature and points, and lays out their groups; sizes the next cache. Manifolds whose
  // bodies are all static or asleep are left out; their cache entries carry over. Nothing of
  // the world is read after this but the step's manifolds and bodies.
  // It may run beside the checks, on manifolds not yet checked: it writes only its own
  // scratch and the next cache (scratch until the step stores it), and returns false, having
  // laid out nothing, at a manifold whose body index is out of range or whose point count is
  // outside [1, kMaxContactPoints] (the checks then name it).
  // same_inputs: the caller found every manifold's contact_layout_input equal to
  // layout_inputs()'s; then, unless a body changed since (step.bodies_version), it keeps the
  // last layout (layout().kept), which is what colouring them again would give.
  virtual bool load(const ContactStep& step, bool same_inputs = false) = 0;
  // The inputs of the last layout, one per manifold in its input order, while they are this
  // step's candidates: no body changed since and the step has as many manifolds; else null.
  virtual const ContactLayoutInput* layout_inputs(std::uint64_t bodies_version,
                                                  std::size_t manifolds) const = 0;
  // The team's threads take the colours' groups in chunks (the overflow: each its share),
  // before prepare (a barrier between): matches each manifold with the last step's cache
  // (once: store reuses the match) and fills its lane.
  virtual void pack(const solver::Share&) = 0;
  virtual const ContactLayout& layout() const = 0;
  bool empty() const { return layout().manifolds == 0; }
  // Each thread its share; prepare ends without a barrier, the others with one per colour.
  virtual void prepare(const simd::BodyArrays&, const simd::SubstepContext&,
                       const solver::Share&) = 0;
  virtual void warm_start(const simd::BodyArrays&, const simd::SubstepContext&,
                          const simd::ContactContext&, const solver::Share&) = 0;
  // With warm starting off, before each sub-step's solve: every lane's accumulated impulses
  // to zero (each thread the groups it solves; the overflow on thread 0).
  virtual void clear_impulses(const solver::Share&) = 0;
  // `friction`: the friction rows too (ContactSettings::friction_while_solving), or only the
  // normal and rolling rows.
  virtual void solve(const simd::BodyArrays&, const simd::SubstepContext&,
                     const simd::ContactContext&, bool friction, const solver::Share&) = 0;
  virtual void relax(const simd::BodyArrays&, const simd::SubstepContext&,
                     const simd::ContactContext&, const solver::Share&) = 0;
  virtual void restitute(const simd::BodyArrays&, const simd::SubstepContext&,
                         const simd::ContactContext&, const solver::Share&) = 0;
  // Each thread its share, after the last contact pass (a barrier between): the next cache's
  // entries, in the solver's order (the readings are read from them on demand).
  virtual void store(const solver::Share&) = 0;
};

std::unique_ptr<ContactSolver> make_contact_solver(SimdWidth width);

// The contact spring of one sub-step h.
simd::ContactContext make_contact_context(const ContactSettings& settings, float h);

}  // namespace softstep
