// The scene options `softstep profile` and `softstep sweep` share: which scene, its size, and
// the spring of its joints. One parser and one builder, so both commands run the same scenes.
#pragma once

#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "scenes/bridge_scene.hpp"
#include "scenes/chain_scene.hpp"
#include "scenes/grid_scene.hpp"
#include "scenes/hinge_chain.hpp"
#include "scenes/prismatic_stack.hpp"
#include "scenes/ragdoll_scene.hpp"
#include "scenes/suspension_bridge.hpp"
#include "scenes/vehicle_scene.hpp"
#include "tool/arguments.hpp"

namespace CLI {
class App;
}

namespace softstep::tool {

// What the scenes are, for the commands' help.
extern const char* const kSceneHelp;

struct SceneChoice {
  std::string scene = "chain";  // chain, grid, bridge, a joint, talk or collision scene, or a file
  scenes::ChainOptions chain;
  scenes::GridOptions grid;
  scenes::BridgeOptions bridge;
  scenes::HingeChainOptions hinge;     // tool/joint_scenes.cpp
  scenes::PrismaticStackOptions stack;
  scenes::RagdollOptions ragdoll;
  scenes::VehicleOptions vehicle;                 // tool/talk_scenes.cpp
  scenes::SuspensionBridgeOptions suspension;
  int count = 1;  // --count: ragdolls, cars, bridges or pile bodies (talk_scenes.cpp, one option)
  int pyramid_base = 100;  // pyramid --base (tool/collision_scenes.cpp)
  int pile_count = 1000;   // pile: bodies dropped (--count)
  std::string spring_text;  // "rigid" or "spring F Hz, zeta Z"
  // Parsed straight into; turned into the scenes' springs and masses once parsing is complete.
  double hertz = 0.0, zeta = 0.7, end_mass = 1.0;
  double hinge_limit_deg = 0.0;  // hinge-chain --limit, degrees
  std::string joint = "ball", layout = "horizontal";
  // A recording (World::start_recording): `softstep profile` replays it (profile_recording.hpp).
  bool from_recording = false;
  // A scene file: its text (read once, loaded for every run) and its settings.
  bool from_file = false;
  std::string file_text;
  WorldSettings file_settings;
};

// Declares the scene (a positional) and its options on `command`. Once the command line is
// parsed, an option of another scene, or --zeta without --hertz, is a CLI::ValidationError
// naming it. `choice` must outlive the parse.
void add_scene_options(CLI::App& command, SceneChoice& choice);

// A scene's own figures for the sweep's CSV, one value each, NaN where the scene has none or
// the run was too short to measure it.
struct SceneReadings {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double bounce_hz = kNone;            // vehicle: the first car's bounce
  double bounce_error = kNone;         // (bounce - the springs' hertz) / the springs' hertz
  double ride_height_error_m = kNone;  // vehicle: chassis centre - promised ride height
  double sag_error = kNone;  // suspension-bridge: (sag under the load - static) / static
  double crossing_s = kNone;           // suspension-bridge: the cart's time from pier to pier
};

// A built scene: what the reports need to know about it.
struct SceneRun {
  std::string description;
  std::vector<BodyId> bodies;  // the dynamic ones
  std::vector<JointId> joints;
  double rows = 0.0;  // constraint rows
  // Path length through the bodies over the rest length: the worst chain or grid column, the
  // bridge's deck. Empty for a scene file (the tool does not know its chains).
  std::function<double()> stretch_ratio;
  // How far below its start the lowest body could ever hang, m (the potential-energy datum
  // of the sweep's energy drift). A scene file: the diagonal of its bodies' bounding box.
  double reach = 0.0;
  // The worst joint-limit violation now, degrees (a cone, twist or hinge limit), for the
  // scenes whose limits the tool knows (ragdoll); empty otherwise.
  std::function<double()> limit_violation_deg;
  // A scene's own reading (vehicle: bounce and ride height; suspension-bridge: sag), fed
  // after every step by after_step and printed at the end; empty when the scene has none.
  std::function<void()> after_step;
  std::function<std::string()> reading;
  std::function<SceneReadings()> readings;  // the same for the sweep's CSV
  // The scene's contacts for the world's poses now, from its own narrow phase (vehicle,
  // suspension-bridge) or Bullet's (pyramid, pile), valid until the next call; empty for
  // scenes without contacts.
  std::function<std::span<const ContactManifold>()> contacts;
};

// One step of the scene: with its contacts when it has any.
void step_scene(World& world, const SceneRun& run, double dt);

// True when the file starts with a recording's signature (a scene file is JSON).
bool is_recording_file(const std::string& path);

// The settings a run starts from: the scene file's, or the defaults for a built-in scene. The
// commands then apply the solver options they were given.
WorldSettings scene_settings(const SceneChoice& choice);

// Builds the scene into `world` (which holds the run's settings): a scene file's world
// replaces it, keeping those settings.
SceneRun build_scene(World& world, const SceneChoice& choice);

// A world loaded from a file (a scene file, a recording's initial scene) as a SceneRun:
// its dynamic bodies, its joints, and a description starting with `name`.
SceneRun describe_world(const World& world, const std::string& name);
std::vector<BodyId> dynamic_bodies(const World& world);

// The bodies' centres now, m.
std::vector<Eigen::Vector3d> positions(const World& world, const std::vector<BodyId>& bodies);

}  // namespace softstep::tool
