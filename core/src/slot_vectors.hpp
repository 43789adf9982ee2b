// The world's body and joint slots, as the solver's passes take them (on huge pages:
// paged_vector.hpp says why).
#pragma once

#include "paged_vector.hpp"

namespace softstep {

struct BodySlot;
struct JointSlot;
using BodySlots = PagedVector<BodySlot>;
using JointSlots = PagedVector<JointSlot>;

}  // namespace softstep
