// Walking the world and the caller's values kept with bodies and joints (issue 17, hook 10).
// Nothing here changes what the world simulates: user data is neither validated nor hashed.
#include "world_impl.hpp"

namespace softstep {

namespace {
// The live slots' ids, in slot order.
template <class Id, class Slot>
std::vector<Id> live_ids(const PagedVector<Slot>& slots, std::size_t live) {
  std::vector<Id> ids;
  ids.reserve(live);
  for (std::uint32_t s = 0; s < slots.size(); ++s) {
    if (slots[s].alive) ids.push_back({s, slots[s].generation});
  }
  return ids;
}
}  // namespace

std::vector<BodyId> World::body_ids() const {
  return live_ids<BodyId>(impl_->bodies, impl_->body_count);
}

std::vector<JointId> World::joint_ids() const {
  return live_ids<JointId>(impl_->joints, impl_->joint_count);
}

void World::set_user_data(BodyId id, std::uint64_t value) {
  impl_->bodies[body_slot(*impl_, "set_user_data", "body", id)].user_data = value;
}

std::uint64_t World::user_data(BodyId id) const {
  return impl_->bodies[body_slot(*impl_, "user_data", "body", id)].user_data;
}

void World::set_user_data(JointId id, std::uint64_t value) {
  impl_->joints[joint_slot(*impl_, "set_user_data", id)].user_data = value;
}

std::uint64_t World::user_data(JointId id) const {
  return impl_->joints[joint_slot(*impl_, "user_data", id)].user_data;
}

}  // namespace softstep
