// Soft-chain scenes: N links per chain, M parallel chains, ball or distance joints, rigid or
// sprung, the first link jointed to the static world. Used by the softstep tool, the
// benchmarks and the tests, so all three measure the same scene.
#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

enum class ChainJoint { Ball, Distance };
enum class ChainLayout {
  Horizontal,  // laid out along +x at rest: swings down under gravity
  Hanging,     // laid out straight down (-y) from the anchor: starts in equilibrium
};

struct ChainOptions {
  int links = 1000;  // links per chain, >= 1
  int chains = 1;    // parallel chains, >= 1
  ChainJoint joint = ChainJoint::Ball;
  Spring spring = Spring::rigid();
  ChainLayout layout = ChainLayout::Horizontal;
  double link_mass = 1.0;  // kg, solid spheres
  // Per-link masses, first link first (kg); when not empty they replace link_mass and the
  // chain has as many links as entries (links is ignored).
  std::vector<double> link_masses;
  double inertia_scale = 1.0;  // multiplies every link's sphere inertia (huge or tiny inertia)
  double linear_damping = 0.0;   // 1/s, every link's
  double angular_damping = 0.0;  // 1/s, every link's
  double tilt = 0.0;           // rad: the layout direction turned about z (a hanging chain swings)
  // Extra distance between the anchors of each joint at creation, m, first joint first (a
  // chain laid out already stretched to its equilibrium); empty: none.
  std::vector<double> joint_gaps;
  // Distance joints' limits, m (a rope: Spring::free() and max_length = link_spacing).
  double min_length = 0.0;
  double max_length = std::numeric_limits<double>::infinity();
  double link_radius = 0.1;    // m
  double link_spacing = 0.25;  // m, centre to centre
  double chain_spacing = 1.0;  // m, between parallel chains (along z)
};

struct ChainScene {
  std::vector<BodyId> anchors;             // one static body per chain
  std::vector<std::vector<BodyId>> links;  // [chain][link]
  std::vector<JointId> joints;             // all joints, chain by chain, from the anchor out
};

ChainScene build_chain(World& world, const ChainOptions& options);

struct JointErrors {
  double max = 0.0;  // m
  double rms = 0.0;  // m
};
JointErrors joint_errors(const World& world, std::span<const JointId> joints);

// Rows one joint of the scene contributes to the solver (ball 3, distance 1).
int rows_per_joint(ChainJoint joint);

}  // namespace softstep::scenes
