// Checks of the step's contacts. Each throws InvalidArgument
// naming the field as "contacts[i].points[k].separation"; nothing is changed before all pass.
#pragma once

#include <span>
#include <string_view>

#include "contacts/contact_cache.hpp"
#include "softstep/contacts.hpp"
#include "world_impl.hpp"

namespace softstep::validation {

// next: the step's next warm-start cache, whose index of the manifolds' keys this fills
// (ContactCache::index_step; it finds the repeated keys). Scratch until the step stores it.
void contacts(std::string_view call, const World::Impl& world,
              std::span<const ContactManifold> manifolds, ContactCache& next);

}  // namespace softstep::validation
