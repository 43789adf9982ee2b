#include "scenes/chain_scene.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softstep::scenes {

ChainScene build_chain(World& world, const ChainOptions& o) {
  const int links = o.link_masses.empty() ? o.links : static_cast<int>(o.link_masses.size());
  if (links < 1 || o.chains < 1) {
    throw std::invalid_argument("build_chain: links and chains must be >= 1 (links " +
                                std::to_string(o.links) + ", chains " + std::to_string(o.chains) +
                                ")");
  }
  const Eigen::Vector3d straight = o.layout == ChainLayout::Horizontal
                                       ? Eigen::Vector3d(o.link_spacing, 0.0, 0.0)
                                       : Eigen::Vector3d(0.0, -o.link_spacing, 0.0);
  const Eigen::Vector3d step = Eigen::AngleAxisd(o.tilt, Eigen::Vector3d::UnitZ()) * straight;
  ChainScene scene;
  scene.links.resize(static_cast<std::size_t>(o.chains));
  for (int c = 0; c < o.chains; ++c) {
    const Eigen::Vector3d origin(0.0, 0.0, c * o.chain_spacing);
    BodyDef anchor_def;
    anchor_def.type = BodyType::Static;
    anchor_def.position = origin;
    BodyId previous = world.create_body(anchor_def);
    scene.anchors.push_back(previous);
    Eigen::Vector3d position = origin;
    for (int i = 0; i < links; ++i) {
      const double gap = o.joint_gaps.empty() ? 0.0 : o.joint_gaps[static_cast<std::size_t>(i)];
      position += step + gap * step.normalized();
      const double mass =
          o.link_masses.empty() ? o.link_mass : o.link_masses[static_cast<std::size_t>(i)];
      BodyDef link;
      link.position = position;
      link.mass = mass;
      link.inertia = solid_sphere_inertia(mass, o.link_radius) * o.inertia_scale;
      link.linear_damping = o.linear_damping;
      link.angular_damping = o.angular_damping;
      const BodyId body = world.create_body(link);
      scene.links[static_cast<std::size_t>(c)].push_back(body);
      if (o.joint == ChainJoint::Ball) {
        BallJointDef j;
        j.body_a = previous;
        j.body_b = body;
        j.local_anchor_a = 0.5 * step;
        j.local_anchor_b = -0.5 * step;
        j.spring = o.spring;
        scene.joints.push_back(world.create_ball_joint(j));
      } else {
        DistanceJointDef j;
        j.body_a = previous;
        j.body_b = body;
        j.rest_length = o.link_spacing;
        j.min_length = o.min_length;
        j.max_length = o.max_length;
        j.spring = o.spring;
        scene.joints.push_back(world.create_distance_joint(j));
      }
      previous = body;
    }
  }
  return scene;
}

JointErrors joint_errors(const World& world, std::span<const JointId> joints) {
  JointErrors e;
  double sum_sq = 0.0;
  for (const JointId j : joints) {
    const double err = world.joint_reading(j).error;
    e.max = std::max(e.max, err);
    sum_sq += err * err;
  }
  e.rms = joints.empty() ? 0.0 : std::sqrt(sum_sq / static_cast<double>(joints.size()));
  return e;
}

int rows_per_joint(ChainJoint joint) {
  return joint == ChainJoint::Ball ? 3 : 1;
}

}  // namespace softstep::scenes
