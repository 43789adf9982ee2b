// How each joint type is written to and read from a scene file: one entry per type, keyed by
// the name the file gives in "type". A new joint type is one read and one write function and
// one line in the table (joint_formats.cpp); the scene reader and writer do not change.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "json_reader.hpp"
#include "softstep/world.hpp"

namespace softstep::scene {

// A body's index in the file's "bodies" array, from its id.
class BodyIndex {
 public:
  explicit BodyIndex(const std::vector<BodyId>& bodies);
  // Names each body by its slot (recordings: the replay gets the same ids).
  static BodyIndex by_slot() { return BodyIndex(); }
  std::size_t operator()(BodyId id) const { return identity_ ? id.index : of_slot_[id.index]; }

 private:
  BodyIndex() : identity_(true) {}
  bool identity_ = false;
  std::vector<std::size_t> of_slot_;
};

struct JointFormat {
  const char* name;  // the file's "type"
  JointType type;
  // Creates the joint from its fields ("type" already read). Fields are read through
  // `fields`, so each bad one is reported at its JSON path.
  JointId (*read)(World& world, ObjectReader& fields, const std::vector<BodyId>& bodies);
  // Writes every field of the joint but "type".
  void (*write)(const World& world, JointId id, const BodyIndex& index, nlohmann::json& out);
  // Changes joint `id` in place (World::set_joint) to the fields `write` wrote.
  void (*set)(World& world, JointId id, ObjectReader& fields, const std::vector<BodyId>& bodies);
};

std::span<const JointFormat> joint_formats();
// nullptr when no joint type has that name.
const JointFormat* joint_format(const std::string& name);
const JointFormat& joint_format(JointType type);

nlohmann::json spring_json(const Spring& spring);
nlohmann::json vector_json(const Eigen::Vector3d& v);

}  // namespace softstep::scene
