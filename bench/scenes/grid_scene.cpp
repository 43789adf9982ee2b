#include "scenes/grid_scene.hpp"

#include <numbers>
#include <stdexcept>
#include <string>

namespace softstep::scenes {

GridScene build_grid(World& world, const GridOptions& o) {
  if (o.size < 2)
    throw std::invalid_argument("build_grid: size must be >= 2, got " + std::to_string(o.size));
  const double mass = o.density * 4.0 / 3.0 * std::numbers::pi * o.radius * o.radius * o.radius;
  const auto n = static_cast<std::size_t>(o.size);
  GridScene scene;
  scene.bodies.reserve(n * n);
  for (std::size_t row = 0; row < n; ++row) {
    for (std::size_t col = 0; col < n; ++col) {
      BodyDef def;
      def.type = row == 0 ? BodyType::Static : BodyType::Dynamic;
      def.position = {static_cast<double>(col) * o.spacing, -static_cast<double>(row) * o.spacing,
                      0.0};
      def.mass = mass;
      def.inertia = solid_sphere_inertia(mass, o.radius);
      scene.bodies.push_back(world.create_body(def));
    }
  }
  const auto join = [&](BodyId a, BodyId b, const Eigen::Vector3d& offset) {
    BallJointDef j;
    j.body_a = a;
    j.body_b = b;
    j.local_anchor_a = 0.5 * offset;
    j.local_anchor_b = -0.5 * offset;
    j.spring = o.spring;
    scene.joints.push_back(world.create_ball_joint(j));
  };
  for (std::size_t row = 0; row < n; ++row) {
    for (std::size_t col = 0; col < n; ++col) {
      const BodyId body = scene.bodies[row * n + col];
      if (col + 1 < n && row > 0)
        join(body, scene.bodies[row * n + col + 1], {o.spacing, 0.0, 0.0});
      if (row + 1 < n) join(body, scene.bodies[(row + 1) * n + col], {0.0, -o.spacing, 0.0});
    }
  }
  return scene;
}

}  // namespace softstep::scenes
