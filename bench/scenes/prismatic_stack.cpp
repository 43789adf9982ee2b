#include "scenes/prismatic_stack.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softstep::scenes {

PrismaticStackScene build_prismatic_stack(World& world, const PrismaticStackOptions& o) {
  if (o.columns < 1 || o.height < 1) {
    throw std::invalid_argument("build_prismatic_stack: columns and height must be >= 1 (columns " +
                                std::to_string(o.columns) + ", height " +
                                std::to_string(o.height) + ")");
  }
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.columns))));
  PrismaticStackScene scene;
  scene.columns.resize(static_cast<std::size_t>(o.columns));
  for (int c = 0; c < o.columns; ++c) {
    const Eigen::Vector3d base(1.0 * (c % side), 0.0, 1.0 * (c / side));
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.position = base;
    BodyId below = world.create_body(ground);
    scene.grounds.push_back(below);
    for (int i = 0; i < o.height; ++i) {
      BodyDef d;
      d.position = base + Eigen::Vector3d(0.0, o.spacing * (i + 1), 0.0);
      d.mass = o.mass;
      d.inertia = Eigen::Matrix3d::Identity() * (o.mass * 0.3 * 0.3 / 6.0);  // cube, side 0.3
      const BodyId body = world.create_body(d);
      scene.columns[static_cast<std::size_t>(c)].push_back(body);
      // Anchors at both centres: translation = (centre B - centre A) . y - spacing, so the
      // frames are built by hand (frames_at would put translation 0 at one shared point).
      PrismaticJointDef j;
      j.body_a = below;
      j.body_b = body;
      j.frame_a.local_anchor = {0.0, o.spacing, 0.0};
      j.frame_a.local_axis = Eigen::Vector3d::UnitY();
      j.frame_a.local_reference = Eigen::Vector3d::UnitX();
      j.frame_b.local_anchor = Eigen::Vector3d::Zero();
      j.frame_b.local_axis = Eigen::Vector3d::UnitY();
      j.frame_b.local_reference = Eigen::Vector3d::UnitX();
      j.spring = o.spring;
      j.limit = o.limit;
      j.motor = o.motor;
      scene.joints.push_back(world.create_joint(j));
      below = body;
    }
  }
  return scene;
}

}  // namespace softstep::scenes
