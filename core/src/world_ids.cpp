// Listing what a world holds, for code that walks it from outside (scene files, the viewer).
#include "world_impl.hpp"

namespace softstep {

std::vector<BodyId> World::body_ids() const {
  std::vector<BodyId> ids;
  ids.reserve(impl_->body_count);
  for (std::uint32_t slot = 0; slot < impl_->bodies.size(); ++slot) {
    if (impl_->bodies[slot].alive) ids.push_back({slot, impl_->bodies[slot].generation});
  }
  return ids;
}

std::vector<JointId> World::joint_ids() const {
  std::vector<JointId> ids;
  ids.reserve(impl_->joint_count);
  for (std::uint32_t slot = 0; slot < impl_->joints.size(); ++slot) {
    if (impl_->joints[slot].alive) ids.push_back({slot, impl_->joints[slot].generation});
  }
  return ids;
}

}  // namespace softstep
