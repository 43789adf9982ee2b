// What a world that has stepped holds beyond its bodies and joints, and a scene file keeps so
// that it reloads into the same world (the same state_hash, the same next step): each joint's
// warm-start impulses ("impulse") and unwrapped hinge angle ("unwrapped_angle"), each body's
// rest time towards sleep ("sleep_time"), the sleeping islands. Written only when not zero, so
// a scene saved before its first step has none. Not kept: the ids of destroyed bodies and
// joints, and with them the joints' colouring, which depends on the order of every joint
// created and destroyed (graph_coloring.hpp), not only on the joints there are.
#pragma once

#include "joint_formats.hpp"
#include "json_reader.hpp"
#include "softstep/world.hpp"

namespace softstep::scene {

// The top-level "solver_state": the last step's sub-step (s) and whether joints were created
// since, which the geometric inertia of the next step depends on, the contacts' warm-start
// cache (contact_cache_format.hpp) and the sleeping islands ("sleeping_islands": each an
// array of body indices). Absent before a first step. The reader applies it after every body
// and joint is created.
std::string world_state_text(const World& world, const BodyIndex& index);  // "": nothing to keep
void read_world_state(const Source& source, const json& solver_state,
                      const std::vector<BodyId>& bodies, World& world);

void write_joint_state(const World& world, JointId id, json& joint);
void write_body_state(const World& world, BodyId id, json& body);

// Read before the joint's or body's own fields (whose reader rejects keys it does not know),
// applied after it is created.
class JointStateReader {
 public:
  explicit JointStateReader(ObjectReader& fields);
  void apply(World& world, JointId id) const;

 private:
  ObjectReader& fields_;
  const json& impulse_;
  double angle_;
};

// create_body normalizes the orientation it is given; a world that has stepped keeps one a
// few ulps off unit, and the file has it to the bit: the loaded body gets it exactly (it
// passed create_body's check of being a unit quaternion within 1e-3).
void keep_exact_orientation(World& world, BodyId id, const Quaternion& saved);

double read_sleep_time(ObjectReader& fields);
void apply_sleep_time(World& world, BodyId id, double sleep_time);

}  // namespace softstep::scene
