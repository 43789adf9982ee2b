#include "scenes/joint_zoo.hpp"

#include <numbers>
#include <stdexcept>
#include <string>

#include "scenes/joint_at.hpp"

namespace softstep::scenes {
namespace {

constexpr double kSpacing = 0.3;  // m, centre to centre along a chain

JointId create(World& world, ZooJoint kind, BodyId a, BodyId b, const Eigen::Vector3d& point,
               int k) {
  // Hinge axes alternate between the swing plane's normal and a tilted one, slide axes
  // between the chain's direction and a tilted one, so the chains move in 3D.
  const Eigen::Vector3d hinge = k % 2 == 0 ? Eigen::Vector3d::UnitZ()
                                           : Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
  const Eigen::Vector3d slide = k % 2 == 0 ? Eigen::Vector3d::UnitX()
                                           : Eigen::Vector3d(1.0, -0.4, 0.2).normalized();
  switch (kind) {
    case ZooJoint::RevolutePlain:
    case ZooJoint::RevoluteLimit:
    case ZooJoint::RevoluteMotor:
    case ZooJoint::RevoluteSpring:
    case ZooJoint::RevoluteAll: {
      auto j = joint_at<RevoluteJointDef>(world, a, b, point, hinge);
      const bool all = kind == ZooJoint::RevoluteAll;
      if (kind == ZooJoint::RevoluteLimit) j.limit = {true, -0.4, 0.3};
      if (all) j.limit = {true, -170.0 * std::numbers::pi / 180.0, 170.0 * std::numbers::pi / 180.0};
      if (kind == ZooJoint::RevoluteMotor || all) j.motor = {true, 1.5, 2.0};
      if (kind == ZooJoint::RevoluteSpring || all) j.spring = {Spring::soft(3.0, 0.2), 0.3};
      return world.create_joint(j);
    }
    case ZooJoint::PrismaticPlain:
    case ZooJoint::PrismaticLimit:
    case ZooJoint::PrismaticMotor:
    case ZooJoint::PrismaticSpring:
    case ZooJoint::PrismaticAll: {
      auto j = joint_at<PrismaticJointDef>(world, a, b, point, slide);
      const bool all = kind == ZooJoint::PrismaticAll;
      if (kind == ZooJoint::PrismaticLimit || all) j.limit = {true, -0.05, 0.04};
      if (kind == ZooJoint::PrismaticMotor || all) j.motor = {true, 0.2, 5.0};
      if (kind == ZooJoint::PrismaticSpring || all) j.spring = {Spring::soft(4.0, 0.3), 0.02};
      return world.create_joint(j);
    }
    default: {
      auto j = joint_at<WeldJointDef>(world, a, b, point, Eigen::Vector3d::UnitZ());
      if (kind == ZooJoint::WeldSoftAngular || kind == ZooJoint::WeldSoft)
        j.angular = Spring::soft(5.0, 0.1);
      if (kind == ZooJoint::WeldSoftLinear || kind == ZooJoint::WeldSoft)
        j.linear = Spring::soft(8.0, 0.5);
      return world.create_joint(j);
    }
  }
}

}  // namespace

JointZooScene build_joint_zoo(World& world, const JointZooOptions& o) {
  if (o.chains < 1 || o.links < 1) {
    throw std::invalid_argument("build_joint_zoo: chains and links must be >= 1 (chains " +
                                std::to_string(o.chains) + ", links " + std::to_string(o.links) +
                                ")");
  }
  BodyDef ceiling_def;
  ceiling_def.type = BodyType::Static;
  const BodyId ceiling = world.create_body(ceiling_def);
  JointZooScene scene;
  int k = 0;  // joint counter: which kind, which axis
  for (int c = 0; c < o.chains; ++c) {
    const double z = 0.5 * c;
    BodyId previous = ceiling;
    for (int i = 0; i < o.links; ++i, ++k) {
      BodyDef d;
      d.position = {kSpacing * (i + 1), 0.02 * i, z};
      d.angular_velocity = {0.0, 0.0, 0.5};
      d.mass = 1.0 + 0.1 * (k % 5);
      // A box 0.25 x 0.06 x 0.08 m: unequal principal inertias.
      const double m = d.mass;
      d.inertia = Eigen::Vector3d(m / 12 * (0.06 * 0.06 + 0.08 * 0.08),
                                  m / 12 * (0.25 * 0.25 + 0.08 * 0.08),
                                  m / 12 * (0.25 * 0.25 + 0.06 * 0.06))
                      .asDiagonal();
      const BodyId body = world.create_body(d);
      // Consecutive kinds along a chain, shifted by one per chain, so every kind meets every
      // neighbour and every position in a chain.
      const auto kind = static_cast<ZooJoint>((i + c) % kZooJointKinds);
      const Eigen::Vector3d point(kSpacing * (i + 0.5), 0.02 * i - 0.01, z);
      scene.joints.push_back(create(world, kind, previous, body, point, k));
      scene.kinds.push_back(kind);
      scene.bodies.push_back(body);
      previous = body;
    }
  }
  return scene;
}

}  // namespace softstep::scenes
