// Writes a recording while World::start_recording is on: World's mutating calls each report
// here in one line after they succeed (world.cpp, step.cpp). Buffered: a step costs a few
// bytes and the motion hash.
#pragma once

#include <fstream>
#include <span>
#include <string>

#include "format.hpp"
#include "softstep/world.hpp"

namespace softstep::recording {

class Recorder {
 public:
  // Opens `path` and writes the header with `world` as it is.
  Recorder(const std::string& path, const World& world);
  ~Recorder();  // flushes (a file without its end record replays up to where it stops)

  // A step without contacts is a Step record, one with contacts a ContactStep holding them.
  void step(double dt, std::span<const ContactManifold> contacts, std::uint64_t motion_hash);
  void create_body(const BodyDef& def, BodyId id);
  void destroy_body(BodyId id) { id_record(Tag::DestroyBody, id.index, id.generation); }
  void set_vector(Tag tag, BodyId id, const Eigen::Vector3d& v);
  void set_orientation(BodyId id, const Quaternion& q);
  void set_mass_properties(BodyId id, double mass, const Eigen::Matrix3d& inertia);
  void apply_impulse(BodyId id, const Eigen::Vector3d& impulse, const Eigen::Vector3d& point);
  void apply_force(BodyId id, const Eigen::Vector3d& force, const Eigen::Vector3d& point);
  void apply_torque(BodyId id, const Eigen::Vector3d& torque) {
    set_vector(Tag::ApplyTorque, id, torque);
  }
  void create_joint(const World& world, JointId id);
  void set_joint(const World& world, JointId id);
  void destroy_joint(JointId id) { id_record(Tag::DestroyJoint, id.index, id.generation); }
  void set_settings(const WorldSettings& settings);
  // Writes the end record and closes the file.
  void finish(std::uint64_t state_hash);

 private:
  void id_record(Tag tag, std::uint32_t index, std::uint32_t generation);
  void flush_if_full();

  std::string path_;
  std::ofstream out_;
  ByteWriter buffer_;
};

}  // namespace softstep::recording
