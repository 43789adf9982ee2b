// A hash of the whole world, bit for bit: tests use it to prove a rejected call changed
// nothing, and tools to compare runs for determinism from outside.
#include <cstring>
#include <type_traits>

#include "state_hasher.hpp"
#include "world_impl.hpp"

namespace softstep {

namespace {

// The contacts' warm-start impulses, in the order of their keys (the cache's own order is the
// last step's solver's, or the input's after a destruction or a scene load). Nothing while the
// cache is empty, so worlds without contacts hash as before.
void hash_contact_cache(StateHasher& h, const ContactCache& cache) {
  for (const auto* entry : sorted_entries(cache)) {
    const ContactPairKey& k = entry->key;
    const CachedManifold& c = entry->manifold;
    h.value(k.low);
    h.value(k.high);
    h.value(k.key);
    h.value(c.body_a);
    h.value(static_cast<int>(c.point_count));  // hashed as the int it was
    for (std::size_t p = 0; p < static_cast<std::size_t>(c.point_count); ++p) {
      h.value(c.feature_id[p]);
      h.value(c.normal_impulse[p]);
      h.matrix(c.friction_impulse[p]);
      h.value(c.max_normal_impulse[p]);
    }
    h.matrix(c.rolling_impulse);
  }
}

}  // namespace

std::uint64_t World::state_hash() const {
  const Impl& w = *impl_;
  StateHasher h;
  const WorldSettings& s = w.settings;
  h.matrix(s.gravity);
  h.value(s.substeps);
  h.value(s.solve_iterations);
  h.value(s.max_linear_speed);
  h.value(s.max_rotation_per_substep);
  h.value(s.relax_iterations);
  h.value(s.warm_start);
  h.value(s.rigid_hertz);
  h.value(s.rigid_damping_ratio);
  h.value(s.max_correction_speed);
  h.value(s.geometric_stiffness);
  h.value(s.sleeping);
  h.value(s.sleep_linear_speed);
  h.value(s.sleep_angular_speed);
  h.value(s.time_to_sleep);
  // Only when not the default, so that the golden hashes of iterative worlds still hold.
  if (s.solver != SolverMode::Iterative) h.value(s.solver);
  if (s.contact != ContactSettings{}) {
    h.value(s.contact.hertz);
    h.value(s.contact.damping_ratio);
    h.value(s.contact.max_push_out_speed);
    h.value(s.contact.restitution_threshold);
    // Only when off, so that the hashes of worlds from before the setting still hold.
    if (!s.contact.friction_while_solving) h.value(s.contact.friction_while_solving);
  }
  // Not hashed: simd, threads and specialize, which by design never change a result, so that runs
  // at different widths and thread counts can be compared by hash.
  h.value(w.bodies.size());
  for (const BodySlot& b : w.bodies) {
    h.value(b.generation);
    h.value(b.alive);
    if (!b.alive) continue;
    h.value(b.type);
    h.matrix(b.position);
    h.matrix(b.orientation.coeffs());
    h.matrix(b.linear_velocity);
    h.matrix(b.angular_velocity);
    h.value(b.mass);
    h.matrix(b.inertia);
    h.value(b.gravity_scale);
    h.value(b.linear_damping);
    h.value(b.angular_damping);
    h.matrix(b.force);
    h.matrix(b.torque);
    for (std::uint32_t j : b.joints) h.value(j);
    h.value(b.never_sleep);
    h.value(b.asleep);
    h.value(b.sleep_time);
  }
  h.value(w.joints.size());
  for (std::uint32_t slot = 0; slot < w.joints.size(); ++slot) {
    const JointSlot& j = w.joints[slot];
    h.value(j.generation);
    h.value(j.alive);
    if (!j.alive) continue;
    h.value(j.type);
    h.value(j.body_a);
    h.value(j.body_b);
    h.matrix(j.local_anchor_a);
    h.matrix(j.local_anchor_b);
    const std::array<float, kMaxJointImpulses> impulse = w.joint_impulses(slot);
    JointKinds::with(j.type, [&]<class Kind>() {
      Kind::hash(h, j);
      for (int k = 0; k < Kind::kImpulses; ++k) h.value(impulse[k]);
    });
  }
  for (std::uint32_t f : w.free_bodies) h.value(f);
  for (std::uint32_t f : w.free_joints) h.value(f);
  hash_contact_cache(h, w.contact_cache);
  return h.get();
}

}  // namespace softstep
