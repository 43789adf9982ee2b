// Ragdolls: N figures of 16 bodies (pelvis, two spine segments, head, upper and lower arms,
// hands, upper and lower legs, feet), swing-twist joints at the spine, neck, shoulders, wrists
// and hips, revolute joints at the elbows, knees and ankles, each with anatomical limits and a
// little joint friction. Each ragdoll starts in a T-pose with its pelvis at `height` and hangs
// from a static hook by a rope (a distance joint, free below its length) tied to the pelvis:
// dropped, it falls `rope_length` before the rope catches it, limbs flailing, and settles.
// Laid out on a square grid 2 m apart. Used by `softstep profile ragdoll` and the tests.
#pragma once

#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct RagdollOptions {
  int count = 1;               // >= 1
  double height = 10.0;        // m, the pelvis at the start
  double rope_length = 1.0;    // m of free fall before the rope catches the pelvis
  double friction = 3.0;       // N m of joint friction on every swing-twist, half on hinges
  double limb_damping = 0.5;   // 1/s, linear and angular, on every body
};

struct Ragdoll {
  BodyId pelvis;
  std::vector<BodyId> bodies;        // 16, the pelvis first
  std::vector<JointId> swing_twists;  // spine (2), neck, shoulders, wrists, hips
  std::vector<JointId> hinges;        // elbows, knees, ankles
};

struct RagdollScene {
  std::vector<Ragdoll> ragdolls;
  std::vector<BodyId> hooks;
  std::vector<JointId> ropes;
};

RagdollScene build_ragdolls(World& world, const RagdollOptions& options);

// The worst limit violation now, degrees: a swing-twist's cone or twist (its reading's
// angular_error), a hinge's angle outside its limit.
struct RagdollLimits {
  double swing_twist_degrees = 0.0;
  double hinge_degrees = 0.0;
  double worst() const { return swing_twist_degrees > hinge_degrees ? swing_twist_degrees : hinge_degrees; }
};
RagdollLimits ragdoll_limit_violation(const World& world, const RagdollScene& scene);

}  // namespace softstep::scenes
