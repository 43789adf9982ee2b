// The angular-joint zoo: every kind of revolute, prismatic and weld joint in one world, with
// gravity: plain, limited, motored, sprung and all three at once; rigid and soft welds. Chains
// hang from a static ceiling so the joints share bodies, colours and lane groups. Big enough
// by default (5,121 bodies and joints) that a step is shared between threads (>= 4,096).
// The determinism tests compare its state hash across widths, threads and specialization;
// the benchmarks step it too.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct JointZooOptions {
  int chains = 160;  // >= 1
  int links = 16;    // per chain, >= 1
};

// The joint kinds, in the order the chains cycle through them.
enum class ZooJoint {
  RevolutePlain,
  RevoluteLimit,
  RevoluteMotor,
  RevoluteSpring,
  RevoluteAll,
  PrismaticPlain,
  PrismaticLimit,
  PrismaticMotor,
  PrismaticSpring,
  PrismaticAll,
  WeldRigid,
  WeldSoftAngular,
  WeldSoftLinear,
  WeldSoft,
};
inline constexpr int kZooJointKinds = 14;

struct JointZooScene {
  std::vector<BodyId> bodies;  // dynamic
  std::vector<JointId> joints;
  std::vector<ZooJoint> kinds;  // per joint
};

JointZooScene build_joint_zoo(World& world, const JointZooOptions& options = {});

}  // namespace softstep::scenes
