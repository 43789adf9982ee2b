// Sleeping islands. An island is a set of movable bodies linked by joints (a static body
// links nothing: two chains hanging from one ceiling are two islands). It is found only
// among awake bodies, only on a step where some body has rested long enough, so a world at
// rest pays nothing per step for sleeping and an awake world pays one pass over its awake
// bodies. Everything runs on one thread in slot order: deterministic.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "world_impl.hpp"

namespace softstep {

void World::Impl::touch(std::uint32_t body_slot) {
  BodySlot& b = bodies[body_slot];
  if (b.asleep) wake_island(b.island);
  b.sleep_time = 0.0;
}

void World::Impl::wake_island(std::uint32_t island) {
  for (std::uint32_t s : islands[island]) {
    bodies[s].asleep = false;
    bodies[s].sleep_time = 0.0;
  }
  islands[island].clear();
  free_islands.push_back(island);
  --sleeping_islands;
  unpack_joints();  // its joints go back into the lanes with the impulses they slept with
  content_changed();
}

void World::Impl::wake_all() {
  for (std::uint32_t i = 0; i < islands.size(); ++i) {
    if (!islands[i].empty()) wake_island(i);
  }
}

void World::Impl::sleep_island(const std::vector<std::uint32_t>& members) {
  std::uint32_t island;
  if (!free_islands.empty()) {
    island = free_islands.back();
    free_islands.pop_back();
  } else {
    island = static_cast<std::uint32_t>(islands.size());
    islands.emplace_back();
  }
  islands[island] = members;
  for (std::uint32_t s : members) {
    BodySlot& b = bodies[s];
    b.asleep = true;
    b.island = island;
    // Resting bodies stop: a sleeping body's pose is exactly where it fell asleep, and it
    // wakes from rest.
    if (b.type == BodyType::Dynamic) {
      b.linear_velocity.setZero();
      b.angular_velocity.setZero();
    }
  }
  ++sleeping_islands;
  unpack_joints();
  content_changed();
}

namespace {
std::uint32_t find_root(std::vector<std::uint32_t>& root, std::uint32_t s) {
  while (root[s] != s) {
    root[s] = root[root[s]];
    s = root[s];
  }
  return s;
}
}  // namespace

World::Impl::RestTest World::Impl::rest_test(double dt) const {
  const WorldSettings& st = settings;
  if (!st.sleeping) return {};
  // A body rests when both its velocity and what the step moved it are below the sleep
  // speeds. The velocity alone is not enough: a joint left wide open (created apart, or
  // stretched) is closed by the solve pass's bounded correction, and the relax pass then
  // takes that speed out again, so the body moves every step while its velocity reads
  // zero; it fell asleep 1.6 m from its anchor and stayed there (issue 17, bug 2).
  const double moved = st.sleep_linear_speed * dt;
  const double turned =
      std::sin(std::min(0.5 * st.sleep_angular_speed * dt, 0.5 * std::numbers::pi));
  return {true, dt, static_cast<float>(moved * moved), static_cast<float>(turned * turned)};
}

bool World::Impl::update_rest_time(BodySlot& b, const RestTest& test) const {
  const WorldSettings& st = settings;
  const bool resting = !b.never_sleep && b.linear_velocity.norm() <= st.sleep_linear_speed &&
                       b.angular_velocity.norm() <= st.sleep_angular_speed &&
                       b.step_moved2 <= test.moved2 && b.step_turned2 <= test.turned2;
  b.sleep_time = resting ? b.sleep_time + test.dt : 0.0;
  return b.sleep_time >= st.time_to_sleep;
}

void World::Impl::update_sleep(bool some_ready) {
  if (!settings.sleeping || !some_ready) return;
  const WorldSettings& st = settings;
  const std::vector<std::uint32_t>& awake = solver_bodies.movable;

  // Islands of the awake bodies (union-find over their joints), each with the shortest rest
  // time of its bodies. Joints of awake bodies only link awake bodies: a joint to a sleeping
  // body wakes it.
  island_root.resize(bodies.size());
  island_rest.resize(bodies.size());
  for (std::uint32_t s : awake) island_root[s] = s;
  for (std::uint32_t s : awake) {
    for (std::uint32_t j : bodies[s].joints) {
      const std::uint32_t other = joints[j].body_a == s ? joints[j].body_b : joints[j].body_a;
      if (bodies[other].type == BodyType::Static) continue;
      const std::uint32_t ra = find_root(island_root, s);
      const std::uint32_t rb = find_root(island_root, other);
      if (ra != rb) island_root[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  for (std::uint32_t s : awake) island_rest[find_root(island_root, s)] = st.time_to_sleep;
  for (std::uint32_t s : awake) {
    double& rest = island_rest[find_root(island_root, s)];
    rest = std::min(rest, bodies[s].sleep_time);
  }
  // Members of each island that rested long enough, in slot order. The root is the
  // island's lowest slot (unions keep the lower root), met first in the awake list, so
  // islands are numbered in order of their first body.
  std::vector<std::vector<std::uint32_t>> falling;
  island_index.resize(bodies.size());
  for (std::uint32_t s : awake) {
    const std::uint32_t r = find_root(island_root, s);
    if (island_rest[r] < st.time_to_sleep) continue;
    if (r == s) {
      island_index[r] = static_cast<std::uint32_t>(falling.size());
      falling.emplace_back();
    }
    falling[island_index[r]].push_back(s);
  }
  for (const auto& members : falling) sleep_island(members);
}

}  // namespace softstep
