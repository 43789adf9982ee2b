// The manifolds of a step with contacts, as a recording holds them (Tag::ContactStep):
//
//   u32 count, then per manifold:
//     u32 slot, u32 generation of body A, then of body B
//     3 f64 normal, u8 point count (1..4), u8 flags, f64 friction
//     f64 restitution          if flags & kRestitution
//     f64 rolling resistance   if flags & kRollingResistance
//     2 f64 tangent speed      if flags & kTangentSpeed
//     u64 key                  if flags & kKey
//     2 f64 radius A, radius B if flags & kRadii
//     per point: 3 f64 anchor A, 3 f64 anchor B, f64 separation, u32 feature id
//
// Every value the step reads is kept to the bit (doubles as doubles), so the replay solves the
// same contacts; the fields most contacts leave at zero cost a flag bit instead of their bytes
// (a 4-point manifold without them is 290 bytes).
#pragma once

#include <span>
#include <vector>

#include "byte_reader.hpp"
#include "format.hpp"
#include "softstep/contacts.hpp"

namespace softstep::recording {

void write_contacts(ByteWriter& out, std::span<const ContactManifold> contacts);

// Reads what write_contacts wrote into `contacts` (reusing its storage). A truncated record is
// the reader's RecordingError; a point count or flags no writer makes is a RecordingError from
// `fail` (which names the record). Values are not validated here: the replayed step validates
// them as it would the caller's (a bad one is refused by name).
template <class Fail>
void read_contacts(ByteReader& in, std::vector<ContactManifold>& contacts, Fail&& fail);

// The smallest a manifold can be in the file: a count is checked against it before anything
// is allocated.
inline constexpr std::size_t kMinManifoldBytes = 4 * 4 + 3 * 8 + 2 + 8 + (6 * 8 + 8 + 4);

enum ContactFlags : std::uint8_t {
  kRestitution = 1,
  kRollingResistance = 2,
  kTangentSpeed = 4,
  kKey = 8,
  kRadii = 16,  // a round shape: written only then, so files without radii read as before
  kAllContactFlags = 31,
};

template <class Fail>
void read_contacts(ByteReader& in, std::vector<ContactManifold>& contacts, Fail&& fail) {
  const auto count = in.get<std::uint32_t>("a step's contact count");
  in.need(std::size_t{count} * kMinManifoldBytes, "a step's contacts");
  contacts.assign(count, ContactManifold{});
  const auto vector = [&](Eigen::Vector3d& v, const char* what) {
    for (int k = 0; k < 3; ++k) v[k] = in.get<double>(what);
  };
  for (std::uint32_t i = 0; i < count; ++i) {
    ContactManifold& m = contacts[i];
    m.body_a.index = in.get<std::uint32_t>("a contact's body");
    m.body_a.generation = in.get<std::uint32_t>("a contact's body");
    m.body_b.index = in.get<std::uint32_t>("a contact's body");
    m.body_b.generation = in.get<std::uint32_t>("a contact's body");
    vector(m.normal, "a contact's normal");
    const auto points = in.get<std::uint8_t>("a contact's point count");
    const auto flags = in.get<std::uint8_t>("a contact's flags");
    if (points < 1 || points > kMaxContactPoints)
      fail("contacts[" + std::to_string(i) + "] has " + std::to_string(points) +
           " points; a manifold has 1 to " + std::to_string(kMaxContactPoints));
    if ((flags & ~kAllContactFlags) != 0)
      fail("contacts[" + std::to_string(i) + "] has unknown flags " + std::to_string(flags));
    m.point_count = points;
    m.friction = in.get<double>("a contact's friction");
    m.restitution = flags & kRestitution ? in.get<double>("a contact's restitution") : 0.0;
    m.rolling_resistance =
        flags & kRollingResistance ? in.get<double>("a contact's rolling resistance") : 0.0;
    if (flags & kTangentSpeed) {
      m.tangent_speed.x() = in.get<double>("a contact's tangent speed");
      m.tangent_speed.y() = in.get<double>("a contact's tangent speed");
    }
    m.key = flags & kKey ? in.get<std::uint64_t>("a contact's key") : 0;
    if (flags & kRadii) {
      m.radius_a = in.get<double>("a contact's radius");
      m.radius_b = in.get<double>("a contact's radius");
    }
    for (int k = 0; k < points; ++k) {
      ContactPoint& p = m.points[static_cast<std::size_t>(k)];
      vector(p.anchor_a, "a contact point's anchor");
      vector(p.anchor_b, "a contact point's anchor");
      p.separation = in.get<double>("a contact point's separation");
      p.feature_id = in.get<std::uint32_t>("a contact point's feature id");
    }
  }
}

}  // namespace softstep::recording
