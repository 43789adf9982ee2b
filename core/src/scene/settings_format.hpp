// WorldSettings in a scene file: every field under its API name, read and written from one
// list so that the two cannot drift apart.
#pragma once

#include <nlohmann/json.hpp>

#include "json_reader.hpp"
#include "softstep/world_settings.hpp"

namespace softstep::scene {

WorldSettings read_settings(ObjectReader& fields);
nlohmann::json settings_json(const WorldSettings& settings);

}  // namespace softstep::scene
