// Checks of the step's contacts. Each throws InvalidArgument
// naming the field as "contacts[i].points[k].separation"; nothing is changed before all pass.
#pragma once

#include <span>
#include <string_view>

#include "softstep/contacts.hpp"
#include "world_impl.hpp"

namespace softstep::validation {

void contacts(std::string_view call, const World::Impl& world,
              std::span<const ContactManifold> manifolds);

}  // namespace softstep::validation
