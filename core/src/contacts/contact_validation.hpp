// Checks of the step's contacts. Each throws InvalidArgument
// naming the field as "contacts[i].points[k].separation"; nothing is changed before all pass.
#pragma once

#include <span>
#include <string_view>

#include "contacts/contact_key_index.hpp"
#include "softstep/contacts.hpp"
#include "world_impl.hpp"

namespace softstep::validation {

// keys: filled with each manifold's body pair and key, valued by its position (it finds the
// repeated ones; the step then indexes its next warm-start cache with it).
void contacts(std::string_view call, const World::Impl& world,
              std::span<const ContactManifold> manifolds, ContactKeyIndex& keys);

}  // namespace softstep::validation
