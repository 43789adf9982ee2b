// The recording file format, version 3 (little-endian throughout):
//
//   header   "SSTEPREC" (8 bytes), u32 version,
//            u64 length + the initial world as a scene file (JSON, scene_save.cpp),
//            u64 World::state_hash() of that world
//   records  u8 tag + payload, in call order (Tag below); a step is f64 dt + u64 motion hash,
//            a step with contacts also holds the manifolds given to it (contact_records.hpp)
//   end      u8 kEnd + u64 World::state_hash() at stop_recording
//
// Bodies and joints are named by their ids (u32 slot, u32 generation): the replayed world was
// checked equal to the recorded one at the start (state_hash covers the ids), so the same
// calls give the same ids. Created bodies and joints are written as their scene-file JSON (a
// joint through the joint-format table), and so is a joint after set_joint, so a new joint
// type needs nothing here.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

namespace softstep::recording {

inline constexpr char kMagic[8] = {'S', 'S', 'T', 'E', 'P', 'R', 'E', 'C'};
// Version 2 added the records ApplyForce, ApplyTorque and SetJoint, version 3 ContactStep and,
// in the initial scene, the contact settings and the contacts' warm-start cache: an older
// reader refuses such a file by its version instead of at the first unknown tag. Files of
// versions 1 and 2 still replay.
inline constexpr std::uint32_t kVersion = 3;
inline constexpr std::uint32_t kOldestVersion = 1;
// The first record tag of versions 2 and 3 (a tag is known from the version it came with on).
inline constexpr std::uint8_t kFirstVersion2Tag = 13;
inline constexpr std::uint8_t kFirstVersion3Tag = 16;

enum class Tag : std::uint8_t {
  Step = 1,                // f64 dt, u64 motion hash after the step
  CreateBody = 2,          // u32 length + body JSON, then the id it got
  DestroyBody = 3,         // id
  SetPosition = 4,         // id, 3 f64
  SetOrientation = 5,      // id, 4 f64 (w, x, y, z)
  SetLinearVelocity = 6,   // id, 3 f64
  SetAngularVelocity = 7,  // id, 3 f64
  SetMassProperties = 8,   // id, f64 mass, 9 f64 inertia (rows)
  ApplyImpulse = 9,        // id, 3 f64 impulse, 3 f64 world point
  CreateJoint = 10,        // u32 length + joint JSON (bodies by slot), then the id it got
  DestroyJoint = 11,       // id
  SetSettings = 12,        // u32 length + settings JSON
  ApplyForce = 13,         // id, 3 f64 force, 3 f64 world point
  ApplyTorque = 14,        // id, 3 f64 torque
  SetJoint = 15,           // id, then u32 length + the joint's JSON after the change
  ContactStep = 16,        // f64 dt, the manifolds (contact_records.hpp), u64 motion hash
  End = 255,               // u64 state hash
};

// Appends little-endian values (this library's targets are little-endian x86-64).
class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    const auto at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &v, sizeof(T));
  }
  void put_text(const std::string& text) {
    put(static_cast<std::uint32_t>(text.size()));
    bytes_ += text;
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

}  // namespace softstep::recording
