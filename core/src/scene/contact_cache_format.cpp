#include "contact_cache_format.hpp"

#include <cmath>

#include "world_impl.hpp"

namespace softstep::scene {

namespace {

constexpr const char* kKey = "contact_cache";

BodyId body_of_word(std::uint64_t word) {
  return {static_cast<std::uint32_t>(word), static_cast<std::uint32_t>(word >> 32)};
}

// An impulse the solver will hold as a float: finite and within float's range.
double impulse_at(const Source& source, const json& list, std::size_t k, const std::string& path) {
  const json& v = list[k];
  if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 3.0e38)
    fail(source, path + "/" + std::to_string(k),
         "expected a finite impulse (N s) within float's range");
  return v.get<double>();
}

}  // namespace

json contact_cache_json(const World& world, const BodyIndex& index) {
  const ContactCache& cache = WorldInternals::of(world).contact_cache;
  json list = json::array();
  for (const auto* entry : sorted_entries(cache)) {
    // Both bodies are alive: destroy_body takes its entries out of the cache.
    const ContactPairKey& k = entry->key;
    const CachedManifold& c = entry->manifold;
    const BodyId low = body_of_word(k.low), high = body_of_word(k.high);
    const bool low_is_a = low.index == c.body_a;
    json j = {{"a", index(low_is_a ? low : high)}, {"b", index(low_is_a ? high : low)}};
    if (k.key != 0) j["key"] = k.key;
    json points = json::array();
    for (std::size_t p = 0; p < static_cast<std::size_t>(c.point_count); ++p) {
      const Eigen::Vector3d& f = c.friction_impulse[p];
      points.push_back({c.feature_id[p], c.normal_impulse[p], f.x(), f.y(), f.z(),
                        c.max_normal_impulse[p]});
    }
    j["points"] = std::move(points);
    if (!c.rolling_impulse.isZero(0.0)) j["rolling_impulse"] = vector_json(c.rolling_impulse);
    list.push_back(std::move(j));
  }
  return list;
}

void read_contact_cache(const Source& source, ObjectReader& solver_state,
                        const std::vector<BodyId>& bodies, World& world) {
  const json& list = solver_state.array(kKey, /*optional=*/true);
  ContactCache cache;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = solver_state.path_of(kKey) + "/" + std::to_string(i);
    ObjectReader fields(source, list[i], path);
    const BodyId a = fields.body("a", bodies), b = fields.body("b", bodies);
    if (a == b) fail(source, fields.path_of("b"), "a contact joins two different bodies");
    std::uint64_t key = 0;
    if (fields.has("key")) {
      const json& v = list[i]["key"];
      if (!v.is_number_unsigned() && !(v.is_number_integer() && v >= 0))
        fail(source, fields.path_of("key"), "expected a whole number from 0 (the manifold key)");
      key = v.get<std::uint64_t>();
      fields.number("key");  // marks it read
    }
    CachedManifold c;
    c.body_a = a.index;
    const json& points = fields.array("points");
    if (points.empty() || points.size() > kMaxContactPoints)
      fail(source, fields.path_of("points"),
           "expected 1 to " + std::to_string(kMaxContactPoints) + " points");
    c.point_count = static_cast<std::uint16_t>(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) {
      const std::string point_path = fields.path_of("points") + "/" + std::to_string(p);
      const json& point = points[p];
      if (!point.is_array() || point.size() != 6)
        fail(source, point_path,
             "expected [feature_id, normal_impulse, friction_x, friction_y, friction_z, "
             "max_normal_impulse]");
      if (!point[0].is_number_integer() || point[0] < 0 || point[0] > 0xffffffffull)
        fail(source, point_path + "/0", "expected a feature id (a whole number from 0 to 2^32-1)");
      c.feature_id[p] = point[0].get<std::uint32_t>();
      c.normal_impulse[p] = impulse_at(source, point, 1, point_path);
      c.friction_impulse[p] = {impulse_at(source, point, 2, point_path),
                               impulse_at(source, point, 3, point_path),
                               impulse_at(source, point, 4, point_path)};
      c.max_normal_impulse[p] = impulse_at(source, point, 5, point_path);
    }
    c.rolling_impulse = fields.vec3("rolling_impulse", Eigen::Vector3d::Zero());
    if (!c.rolling_impulse.allFinite() || c.rolling_impulse.cwiseAbs().maxCoeff() > 3.0e38)
      fail(source, fields.path_of("rolling_impulse"),
           "expected a finite impulse (N m s) within float's range");
    fields.no_other_keys();
    ContactManifold pair;
    pair.body_a = a;
    pair.body_b = b;
    pair.key = key;
    if (!cache.insert(contact_pair_key(pair), c))
      fail(source, path, "a second entry for the same two bodies and key");
  }
  WorldInternals::of(world).settle_contact_readings();
  WorldInternals::of(world).contact_cache = std::move(cache);
}

}  // namespace softstep::scene
