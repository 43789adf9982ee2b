#include "contact_records.hpp"

#include <cmath>

namespace softstep::recording {

void write_contacts(ByteWriter& out, std::span<const ContactManifold> contacts) {
  out.put(static_cast<std::uint32_t>(contacts.size()));
  const auto vector = [&](const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) out.put(v[k]);
  };
  for (const ContactManifold& m : contacts) {
    out.put(m.body_a.index);
    out.put(m.body_a.generation);
    out.put(m.body_b.index);
    out.put(m.body_b.generation);
    vector(m.normal);
    // Tested against zero bit for bit: -0.0 is written out, so the replay gets the same sign.
    const auto nonzero = [](double v) { return std::signbit(v) || v != 0.0; };
    std::uint8_t flags = 0;
    if (nonzero(m.restitution)) flags |= kRestitution;
    if (nonzero(m.rolling_resistance)) flags |= kRollingResistance;
    if (nonzero(m.tangent_speed.x()) || nonzero(m.tangent_speed.y())) flags |= kTangentSpeed;
    if (m.key != 0) flags |= kKey;
    out.put(static_cast<std::uint8_t>(m.point_count));
    out.put(flags);
    out.put(m.friction);
    if (flags & kRestitution) out.put(m.restitution);
    if (flags & kRollingResistance) out.put(m.rolling_resistance);
    if (flags & kTangentSpeed) {
      out.put(m.tangent_speed.x());
      out.put(m.tangent_speed.y());
    }
    if (flags & kKey) out.put(m.key);
    for (int k = 0; k < m.point_count; ++k) {
      const ContactPoint& p = m.points[static_cast<std::size_t>(k)];
      vector(p.anchor_a);
      vector(p.anchor_b);
      out.put(p.separation);
      out.put(p.feature_id);
    }
  }
}

}  // namespace softstep::recording
