// World::motion_hash: what a recording checks after every step. state_hash (FNV-1a over every
// byte of the world) costs more than a 100,000-body step; this one reads each live body's slot,
// pose and velocities as 64-bit words into four independent multiply-xor lanes, so that the
// multiplications overlap instead of waiting on each other.
#include <cstring>

#include "world_impl.hpp"

namespace softstep {

namespace {

std::uint64_t word(double value) {
  std::uint64_t w;
  std::memcpy(&w, &value, sizeof w);
  return w;
}

// One multiply-xor step of a lane.
inline void mix(std::uint64_t& lane, std::uint64_t w) {
  lane = (lane ^ w) * 0x9E3779B97F4A7C15ull;
}

}  // namespace

std::uint64_t World::motion_hash() const {
  // Each body's 14 words go to fixed lanes, so the four lanes stay in registers and their
  // multiplications overlap.
  std::uint64_t l0 = 1, l1 = 2, l2 = 3, l3 = 4;
  const BodySlots& bodies = impl_->bodies;
  for (std::uint32_t slot = 0; slot < bodies.size(); ++slot) {
    const BodySlot& b = bodies[slot];
    if (!b.alive) continue;
    const auto& q = b.orientation.coeffs();
    mix(l0, (std::uint64_t{slot} << 32) | b.generation);
    mix(l1, word(b.position.x()));
    mix(l2, word(b.position.y()));
    mix(l3, word(b.position.z()));
    mix(l0, word(q[0]));
    mix(l1, word(q[1]));
    mix(l2, word(q[2]));
    mix(l3, word(q[3]));
    mix(l0, word(b.linear_velocity.x()));
    mix(l1, word(b.linear_velocity.y()));
    mix(l2, word(b.linear_velocity.z()));
    mix(l3, word(b.angular_velocity.x()));
    mix(l0, word(b.angular_velocity.y()));
    mix(l1, word(b.angular_velocity.z()));
  }
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::uint64_t lane : {l0, l1, l2, l3}) h = (h ^ (lane ^ (lane >> 29))) * 0x100000001b3ull;
  return h;
}

}  // namespace softstep
