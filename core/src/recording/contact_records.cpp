#include "contact_records.hpp"

#include <cmath>
#include <cstring>

namespace softstep::recording {

namespace {

// Puts one manifold's fields into a fixed buffer and appends it in one go: a step of 15,000
// manifolds would otherwise grow the recording's buffer some 40 times per manifold.
class ManifoldBytes {
 public:
  template <class T>
  void put(const T& v) {
    std::memcpy(bytes_ + size_, &v, sizeof v);
    size_ += sizeof v;
  }
  void put(const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) put(v[k]);
  }
  const char* data() const { return bytes_; }
  std::size_t size() const { return size_; }

 private:
  static constexpr std::size_t kMaxBytes =
      kMinManifoldBytes + 8 + 8 + 16 + 8 + 16 + (kMaxContactPoints - 1) * (6 * 8 + 8 + 4);
  char bytes_[kMaxBytes];
  std::size_t size_ = 0;
};

// Tested against zero bit for bit: -0.0 is written out, so the replay gets the same sign.
bool nonzero(double v) { return std::signbit(v) || v != 0.0; }

}  // namespace

void write_contacts(ByteWriter& out, std::span<const ContactManifold> contacts) {
  out.put(static_cast<std::uint32_t>(contacts.size()));
  for (const ContactManifold& m : contacts) {
    ManifoldBytes b;
    b.put(m.body_a.index);
    b.put(m.body_a.generation);
    b.put(m.body_b.index);
    b.put(m.body_b.generation);
    b.put(m.normal);
    std::uint8_t flags = 0;
    if (nonzero(m.restitution)) flags |= kRestitution;
    if (nonzero(m.rolling_resistance)) flags |= kRollingResistance;
    if (nonzero(m.tangent_speed.x()) || nonzero(m.tangent_speed.y())) flags |= kTangentSpeed;
    if (m.key != 0) flags |= kKey;
    if (nonzero(m.radius_a) || nonzero(m.radius_b)) flags |= kRadii;
    b.put(static_cast<std::uint8_t>(m.point_count));
    b.put(flags);
    b.put(m.friction);
    if (flags & kRestitution) b.put(m.restitution);
    if (flags & kRollingResistance) b.put(m.rolling_resistance);
    if (flags & kTangentSpeed) {
      b.put(m.tangent_speed.x());
      b.put(m.tangent_speed.y());
    }
    if (flags & kKey) b.put(m.key);
    if (flags & kRadii) {
      b.put(m.radius_a);
      b.put(m.radius_b);
    }
    for (int k = 0; k < m.point_count; ++k) {
      const ContactPoint& p = m.points[static_cast<std::size_t>(k)];
      b.put(p.anchor_a);
      b.put(p.anchor_b);
      b.put(p.separation);
      b.put(p.feature_id);
    }
    out.bytes().append(b.data(), b.size());
  }
}

}  // namespace softstep::recording
