#include "solver_state.hpp"

#include <algorithm>
#include <cmath>

#include "contact_cache_format.hpp"
#include "joints/joint_registry.hpp"
#include "world_impl.hpp"

namespace softstep::scene {

namespace {

int impulses_of(JointType type) {
  return JointKinds::with(type, []<class Kind>() { return Kind::kImpulses; });
}

// The sleeping islands' bodies by their index in "bodies", each island in slot order.
json sleeping_islands_json(const World::Impl& w, const BodyIndex& index) {
  json islands = json::array();
  for (const std::vector<std::uint32_t>& members : w.islands) {
    if (members.empty()) continue;  // woken, its index free
    json list = json::array();
    for (std::uint32_t slot : members) list.push_back(index(BodyId{slot, w.bodies[slot].generation}));
    islands.push_back(std::move(list));
  }
  return islands;
}

// Puts the file's sleeping islands to sleep as update_sleep would have: each a set of movable
// bodies that no joint links to a movable body outside it (a joint to an awake body would be
// solved against a sleeper that never moves).
void read_sleeping_islands(const Source& source, ObjectReader& fields,
                           const std::vector<BodyId>& bodies, World& world) {
  const char* key = "sleeping_islands";
  const json& list = fields.array(key, /*optional=*/true);
  if (list.empty()) return;
  World::Impl& w = WorldInternals::of(world);
  const std::string path = fields.path_of(key);
  if (!w.settings.sleeping)
    fail(source, path, "sleeping islands in a world whose settings have sleeping off");
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::uint32_t> island_of(w.bodies.size(), kNone);
  std::vector<std::vector<std::uint32_t>> islands(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string island_path = path + "/" + std::to_string(i);
    if (!list[i].is_array() || list[i].empty())
      fail(source, island_path, "expected a non-empty array of body indices in \"bodies\"");
    for (std::size_t k = 0; k < list[i].size(); ++k) {
      const json& v = list[i][k];
      const std::string member_path = island_path + "/" + std::to_string(k);
      if (!v.is_number_integer() || v < 0 || v.get<std::uint64_t>() >= bodies.size())
        fail(source, member_path,
             "expected a body's index in \"bodies\" (the file has " +
                 std::to_string(bodies.size()) + " bodies)");
      const std::uint32_t slot = bodies[v.get<std::size_t>()].index;
      if (w.bodies[slot].type == BodyType::Static)
        fail(source, member_path, "a static body does not sleep");
      if (island_of[slot] != kNone)
        fail(source, member_path, "a body in two sleeping islands (or twice in one)");
      island_of[slot] = static_cast<std::uint32_t>(i);
      islands[i].push_back(slot);
    }
  }
  for (std::size_t i = 0; i < islands.size(); ++i) {
    for (std::uint32_t slot : islands[i]) {
      for (std::uint32_t j : w.bodies[slot].joints) {
        const std::uint32_t other = w.joints[j].body_a == slot ? w.joints[j].body_b : w.joints[j].body_a;
        if (w.bodies[other].type != BodyType::Static && island_of[other] != island_of[slot])
          fail(source, path + "/" + std::to_string(i),
               "a joint links this island to a movable body outside it (an island is every "
               "movable body its joints reach)");
      }
    }
    std::sort(islands[i].begin(), islands[i].end());
    w.sleep_island(islands[i]);
  }
}

}  // namespace

std::string world_state_text(const World& world, const BodyIndex& index) {
  const World::Impl& w = WorldInternals::of(world);
  if (w.last_substep == 0.0) return {};
  json state = {{"last_substep", w.last_substep},
                {"joints_without_history", w.joints_without_history}};
  json contacts = contact_cache_json(world, index);
  if (!contacts.empty()) state["contact_cache"] = std::move(contacts);
  json islands = sleeping_islands_json(w, index);
  if (!islands.empty()) state["sleeping_islands"] = std::move(islands);
  return state.dump();
}

void read_world_state(const Source& source, const json& solver_state,
                      const std::vector<BodyId>& bodies, World& world) {
  ObjectReader fields(source, solver_state, "/solver_state");
  const double h = fields.number("last_substep", 0.0);
  if (!(std::isfinite(h) && h >= 0.0))
    fail(source, fields.path_of("last_substep"), "expected a finite time >= 0 (s)");
  const bool fresh_joints = fields.boolean("joints_without_history", true);
  read_contact_cache(source, fields, bodies, world);
  read_sleeping_islands(source, fields, bodies, world);
  fields.no_other_keys();
  if (h == 0.0) return;
  World::Impl& w = WorldInternals::of(world);
  w.last_substep = h;
  w.joints_without_history = fresh_joints;
}

void write_joint_state(const World& world, JointId id, json& joint) {
  const World::Impl& w = WorldInternals::of(world);
  const JointSlot& slot = w.joints[id.index];
  const std::array<float, kMaxJointImpulses> impulse = w.joint_impulses(id.index);
  const int n = impulses_of(slot.type);
  bool any = false;
  for (int k = 0; k < n; ++k) any = any || impulse[static_cast<std::size_t>(k)] != 0.0f;
  if (any) {
    json list = json::array();
    for (int k = 0; k < n; ++k) list.push_back(impulse[static_cast<std::size_t>(k)]);
    joint["impulse"] = std::move(list);
  }
  if (slot.angle != 0.0) joint["unwrapped_angle"] = slot.angle;
}

void write_body_state(const World& world, BodyId id, json& body) {
  const double rest = WorldInternals::of(world).bodies[id.index].sleep_time;
  if (rest != 0.0) body["sleep_time"] = rest;
}

JointStateReader::JointStateReader(ObjectReader& fields)
    : fields_(fields),
      impulse_(fields.array("impulse", /*optional=*/true)),
      angle_(fields.number("unwrapped_angle", 0.0)) {
  for (std::size_t k = 0; k < impulse_.size(); ++k) {
    // A float, as the solver keeps it: a double beyond float's range would become infinite.
    if (!impulse_[k].is_number() || !std::isfinite(impulse_[k].get<double>()) ||
        std::abs(impulse_[k].get<double>()) > 3.0e38)
      fail(fields_.source(), fields_.path_of("impulse") + "/" + std::to_string(k),
           "expected a finite number (N s or N m s) within float's range");
  }
  if (!std::isfinite(angle_))
    fail(fields_.source(), fields_.path_of("unwrapped_angle"), "expected a finite angle (rad)");
}

void JointStateReader::apply(World& world, JointId id) const {
  World::Impl& w = WorldInternals::of(world);
  JointSlot& slot = w.joints[id.index];
  const std::size_t n = static_cast<std::size_t>(impulses_of(slot.type));
  if (impulse_.size() > n)
    fail(fields_.source(), fields_.path_of("impulse"),
         "a " + std::string(joint_type_name(slot.type)) + " joint keeps " + std::to_string(n) +
             " impulses, the file gives " + std::to_string(impulse_.size()));
  // A new joint is not in the lanes yet: the next pack takes its impulses from the slot.
  for (std::size_t k = 0; k < impulse_.size(); ++k)
    slot.impulse[k] = static_cast<float>(impulse_[k].get<double>());
  slot.angle = angle_;
}

void keep_exact_orientation(World& world, BodyId id, const Quaternion& saved) {
  WorldInternals::of(world).bodies[id.index].orientation = saved;
}

double read_sleep_time(ObjectReader& fields) {
  const double t = fields.number("sleep_time", 0.0);
  if (!(std::isfinite(t) && t >= 0.0))
    fail(fields.source(), fields.path_of("sleep_time"), "expected a finite time >= 0 (s)");
  return t;
}

void apply_sleep_time(World& world, BodyId id, double sleep_time) {
  WorldInternals::of(world).bodies[id.index].sleep_time = sleep_time;
}

}  // namespace softstep::scene
