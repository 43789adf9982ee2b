// A body in a scene file (and in a recording's create_body record): its BodyDef fields under
// their API names.
#pragma once

#include <nlohmann/json.hpp>

#include "json_reader.hpp"
#include "softstep/body.hpp"
#include "softstep/world.hpp"

namespace softstep::scene {

BodyDef read_body(ObjectReader& fields);
nlohmann::json body_json(const BodyDef& def);
// What create_body would be given to make this body as it is now.
BodyDef body_def(const BodyState& state);

}  // namespace softstep::scene
