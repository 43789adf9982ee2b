// Value handles: a slot index plus a generation, so a handle to a destroyed object is
// recognised as stale instead of silently naming whatever reuses its slot.
#pragma once

#include <compare>
#include <cstdint>

namespace softstep {

struct BodyId {
  std::uint32_t index = 0xFFFFFFFFu;
  std::uint32_t generation = 0;
  friend auto operator<=>(const BodyId&, const BodyId&) = default;
};

struct JointId {
  std::uint32_t index = 0xFFFFFFFFu;
  std::uint32_t generation = 0;
  friend auto operator<=>(const JointId&, const JointId&) = default;
};

}  // namespace softstep
