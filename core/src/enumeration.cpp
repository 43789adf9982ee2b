// Walking the world and the caller's values kept with bodies and joints (issue 17, hook 10).
// Nothing here changes what the world simulates: user data is neither validated nor hashed.
#include "world_impl.hpp"

namespace softstep {

std::vector<BodyId> World::body_ids() const {
  const Impl& w = *impl_;
  std::vector<BodyId> ids;
  ids.reserve(w.body_count);
  for (std::uint32_t s = 0; s < w.bodies.size(); ++s) {
    if (w.bodies[s].alive) ids.push_back({s, w.bodies[s].generation});
  }
  return ids;
}

std::vector<JointId> World::joint_ids() const {
  const Impl& w = *impl_;
  std::vector<JointId> ids;
  ids.reserve(w.joint_count);
  for (std::uint32_t s = 0; s < w.joints.size(); ++s) {
    if (w.joints[s].alive) ids.push_back({s, w.joints[s].generation});
  }
  return ids;
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
