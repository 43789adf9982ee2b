// The contacts' warm-start cache in a scene file ("solver_state": {"contact_cache": [...]}):
// what the last step's manifolds left for the next step to start from, so that a world saved
// (or recorded) between contact steps reloads into the same next step. One entry per manifold:
//
//   {"a": body index, "b": body index, "key": manifold key (absent: 0),
//    "points": [[feature_id, normal_impulse, friction_x, friction_y, friction_z,
//                max_normal_impulse], ...]             (1 to 4 points; N s, on B, world frame)
//    "rolling_impulse": [x, y, z]                      (N m s on B; absent: zero)}
//
// "a" is the body that was A in the manifold (impulses are on B). Entries are written in the
// order of their body pair and key, so the same world always writes the same file.
#pragma once

#include <vector>

#include "joint_formats.hpp"
#include "json_reader.hpp"

namespace softstep::scene {

// An empty array when the cache is empty. Entries naming a destroyed body are left out (the
// next step would drop them anyway).
json contact_cache_json(const World& world, const BodyIndex& index);
// Replaces the world's cache with the file's; every field is checked (an error names its path).
void read_contact_cache(const Source& source, ObjectReader& solver_state,
                        const std::vector<BodyId>& bodies, World& world);

}  // namespace softstep::scene
