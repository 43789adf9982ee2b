// Checks of the step's contacts. Each throws InvalidArgument
// naming the field as "contacts[i].points[k].separation"; nothing is changed before all pass.
#pragma once

#include <atomic>
#include <cstddef>
#include <span>
#include <string_view>

#include "contacts/contact_cache.hpp"
#include "contacts/contact_solver.hpp"
#include "softstep/contacts.hpp"
#include "world_impl.hpp"

namespace softstep::validation {

// The checks in two parts, so that the scan can run on the step's threads: scan takes chunks
// of manifolds in turn on every thread of the team (no text, nothing thrown), finish runs on
// the caller after the team: it indexes the keys into `next`, the step's next warm-start cache
// (ContactCache::index_step finds the repeated keys; scratch until the step stores it), and
// throws for the first manifold in input order that breaks a rule or repeats a key. The
// result is the same for any thread count; step.cpp says what sharing them measured. (A split
// tried on 2026-11-26, the keys and the rules as two passes with a fixed half each, took 1.4
// ms against 0.9 on one thread: the worker read its half cold after idling through the
// caller's collision; with chunks taken in turn the caller does most of them when the worker
// starts late.)
// The scan also compares each manifold's layout input with the last layout's (one per
// manifold, or null: no comparison), for the contact solver to keep its layout.
class ContactChecks {
 public:
  ContactChecks(const World::Impl& world, std::span<const ContactManifold> manifolds,
                const ContactLayoutInput* last_layout = nullptr);
  void scan();  // by any number of threads at once, each until no chunk is left
  void finish(std::string_view call, ContactCache& next) const;
  // Every manifold passed and had the last layout's input (false without one to compare).
  bool same_layout_inputs() const { return same_layout_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::size_t kChunk = 512;  // manifolds: about 180 KB of them, 30 a pyramid
  static constexpr std::size_t kNone = ~std::size_t{0};
  const World::Impl& world_;
  std::span<const ContactManifold> manifolds_;
  std::atomic<std::size_t> next_chunk_{0};
  // Every key is last step's at the same position (false once any is not, or unsure).
  std::atomic<bool> unchanged_;
  const ContactLayoutInput* last_layout_;
  std::atomic<bool> same_layout_;
  std::atomic<std::size_t> failure_{kNone};  // the first manifold that breaks a rule
};

}  // namespace softstep::validation
