// A body in a scene file (and in a recording's create_body record): its BodyDef fields under
// their API names.
#pragma once

#include <nlohmann/json.hpp>

#include "json_reader.hpp"
#include "softstep/body.hpp"
#include "softstep/world.hpp"

namespace softstep::scene {

BodyDef read_body(ObjectReader& fields);
// A scene's body may carry the loads applied for its next step (saved after apply_force or
// apply_torque): "force" (N) and "torque" (N m), world frame, zero when absent. Read before
// read_body, which rejects keys it does not know; a recording's create_body has none.
struct PendingLoads {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};
PendingLoads read_pending_loads(ObjectReader& fields);
void write_pending_loads(const BodyState& state, nlohmann::json& body);
nlohmann::json body_json(const BodyDef& def);
// What create_body would be given to make this body as it is now.
BodyDef body_def(const BodyState& state);

}  // namespace softstep::scene
