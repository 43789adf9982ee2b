// The ball/distance feature zoo: every kernel variant of the first two joint types in one world.
#include "scenes/feature_zoo.hpp"

#include <functional>

namespace softstep::scenes {

// Every joint kind the kernels have a variant for, in one world: rigid, soft and free ball
// joints; distance rods, springs with min, max and both limits, ropes (free + max), a free
// spring with a min limit. Links swing under `gravity` from a static ceiling, in chains so
// that joints share bodies, colours and the overflow-free lanes.
void build_feature_zoo(World& world, double damping) {
  BodyDef ceiling_def;
  ceiling_def.type = BodyType::Static;
  const BodyId ceiling = world.create_body(ceiling_def);
  const auto chain = [&](double z, const std::function<void(BodyId, BodyId, int)>& joint) {
    BodyId previous = ceiling;
    for (int i = 0; i < 12; ++i) {
      BodyDef d;
      d.position = {0.3 * (i + 1), 0.02 * i, z};
      d.angular_velocity = {0.0, 0.0, 0.5};
      d.linear_damping = damping;
      const BodyId body = world.create_body(d);
      joint(previous, body, i);
      previous = body;
    }
  };
  const auto ball = [&](Spring spring) {
    return [&world, spring](BodyId a, BodyId b, int) {
      BallJointDef j;
      j.body_a = a;
      j.body_b = b;
      j.local_anchor_b = {-0.15, 0.0, 0.0};
      j.local_anchor_a = {0.15, 0.0, 0.0};
      j.spring = spring;
      world.create_ball_joint(j);
    };
  };
  chain(0.0, ball(Spring::rigid()));
  chain(1.0, ball(Spring::soft(4.0, 0.3)));
  chain(2.0, ball(Spring::free()));
  chain(3.0, [&](BodyId a, BodyId b, int i) {
    DistanceJointDef j;
    j.body_a = a;
    j.body_b = b;
    j.rest_length = 0.3;
    switch (i % 6) {
      case 0:
        j.spring = Spring::rigid();
        break;
      case 1:
        j.spring = Spring::soft(3.0, 0.2);
        j.min_length = 0.25;
        break;
      case 2:
        j.spring = Spring::soft(3.0, 0.2);
        j.max_length = 0.32;
        break;
      case 3:
        j.spring = Spring::soft(2.0, 0.0);
        j.min_length = 0.28;
        j.max_length = 0.35;
        break;
      case 4:
        j.spring = Spring::free();
        j.max_length = 0.31;  // a rope
        break;
      default:
        j.spring = Spring::free();
        j.min_length = 0.29;
        break;
    }
    world.create_distance_joint(j);
  });
}

}  // namespace softstep::scenes
