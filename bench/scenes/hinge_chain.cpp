#include "scenes/hinge_chain.hpp"

#include <stdexcept>
#include <string>

#include "scenes/joint_at.hpp"

namespace softstep::scenes {

HingeChainScene build_hinge_chain(World& world, const HingeChainOptions& o) {
  if (o.links < 1 || o.chains < 1) {
    throw std::invalid_argument("build_hinge_chain: links and chains must be >= 1 (links " +
                                std::to_string(o.links) + ", chains " + std::to_string(o.chains) +
                                ")");
  }
  const double m = o.link_mass;
  const double l = o.link_spacing, w = 0.05;
  const Eigen::Matrix3d inertia =
      Eigen::Vector3d(m / 12 * (2 * w * w), m / 12 * (l * l + w * w), m / 12 * (l * l + w * w))
          .asDiagonal();
  HingeChainScene scene;
  scene.links.resize(static_cast<std::size_t>(o.chains));
  for (int c = 0; c < o.chains; ++c) {
    const Eigen::Vector3d origin(0.0, 0.0, c * 1.0);
    BodyDef anchor;
    anchor.type = BodyType::Static;
    anchor.position = origin;
    BodyId previous = world.create_body(anchor);
    scene.anchors.push_back(previous);
    for (int i = 0; i < o.links; ++i) {
      BodyDef link;
      link.position = origin + Eigen::Vector3d(l * (i + 1), 0.0, 0.0);
      link.mass = m;
      link.inertia = inertia;
      const BodyId body = world.create_body(link);
      scene.links[static_cast<std::size_t>(c)].push_back(body);
      // The hinge halfway between the centres (at the anchor for the first link).
      const Eigen::Vector3d point = origin + Eigen::Vector3d(l * (i + 0.5), 0.0, 0.0);
      if (o.weld) {
        auto j = joint_at<WeldJointDef>(world, previous, body, point, Eigen::Vector3d::UnitZ());
        j.linear = o.weld_linear;
        j.angular = o.weld_angular;
        scene.joints.push_back(world.create_joint(j));
      } else {
        auto j = joint_at<RevoluteJointDef>(world, previous, body, point, Eigen::Vector3d::UnitZ());
        j.limit = o.limit;
        j.motor = o.motor;
        j.spring = o.spring;
        scene.joints.push_back(world.create_joint(j));
      }
      previous = body;
    }
  }
  return scene;
}

}  // namespace softstep::scenes
