// The scene options `softstep profile` and `softstep sweep` share: which scene, its size, and
// the spring of its joints. One parser and one builder, so both commands run the same scenes.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "scenes/bridge_scene.hpp"
#include "scenes/chain_scene.hpp"
#include "scenes/grid_scene.hpp"
#include "scenes/hinge_chain.hpp"
#include "scenes/prismatic_stack.hpp"
#include "tool/arguments.hpp"

namespace softstep::tool {

// The usage lines of the scene options.
extern const char* const kSceneUsage;

struct SceneChoice {
  std::string scene = "chain";  // chain, grid, bridge, hinge-chain or prismatic-stack
  scenes::ChainOptions chain;
  scenes::GridOptions grid;
  scenes::BridgeOptions bridge;
  scenes::HingeChainOptions hinge;     // tool/joint_scenes.cpp
  scenes::PrismaticStackOptions stack;
  std::string spring_text;  // "rigid" or "spring F Hz, zeta Z"
};

// Takes the scene (first positional) and its flags, rejecting another scene's flags.
SceneChoice take_scene_options(Arguments& args);

// A built scene: what the reports need to know about it.
struct SceneRun {
  std::string description;
  std::vector<BodyId> bodies;  // the dynamic ones
  std::vector<JointId> joints;
  double rows = 0.0;  // constraint rows
  // Path length through the bodies over the rest length: the worst chain or grid column, the
  // bridge's deck.
  std::function<double()> stretch_ratio;
  // How far below its start the lowest body could ever hang, m (the potential-energy datum
  // of the sweep's energy drift).
  double reach = 0.0;
};

SceneRun build_scene(World& world, const SceneChoice& choice);

// The bodies' centres now, m.
std::vector<Eigen::Vector3d> positions(const World& world, const std::vector<BodyId>& bodies);

}  // namespace softstep::tool
