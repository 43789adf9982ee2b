#include "tool/scene_options.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "softstep/metrics.hpp"
#include "tool/collision_scenes.hpp"
#include "tool/joint_scenes.hpp"
#include "tool/talk_scenes.hpp"
#include "softstep/scene_file.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

const char* const kSceneHelp =
    "Scenes (default chain), or the path of a scene file (softstep profile ... --save FILE\n"
    "writes one; README \"Your own scene\" has the format), or for profile and sweep a\n"
    "recording (profile ... --record FILE): profile replays it with every step checked,\n"
    "sweep replays its calls at each setting:\n"
    "  chain   N solid 1 kg spheres of radius 0.1 m, 0.25 m apart, laid out horizontally (or\n"
    "          hanging straight down, unstretched), the first link jointed to the static world;\n"
    "          M parallel chains 1 m apart. --end-mass: the last link weighs KG instead (a\n"
    "          mass-ratio chain).\n"
    "  grid    N x N spheres of radius 0.4 m, 1000 kg/m^3, 1 m apart in a vertical plane, top\n"
    "          row static, ball joints to the right and lower neighbours.\n"
    "  bridge  a chain of N links pinned at both ends, K heavy bodies hanging from it on 0.5 m\n"
    "          rods.\n"
    "  hinge-chain  N box links (1 kg, 0.25 x 0.05 x 0.05 m) on revolute joints about z, laid\n"
    "          out along x and swinging down (--links, --chains); --limit: every hinge within\n"
    "          +-DEG; --motor-torque: a motor of at most NM N m driving at --motor-speed W rad/s\n"
    "          (default 0: joint friction); --hertz: torsion springs towards straight.\n"
    "  prismatic-stack  --height H 1 kg cubes per column (default 1000 columns of 10), each on\n"
    "          a vertical slider to the one below, on springs of 4 Hz (or --hertz) within\n"
    "          -0.2 .. +0.1 m of their 0.5 m spacing.\n"
    "  ragdoll --count N ragdolls of 16 bodies (swing-twist spine, neck, shoulders, wrists and\n"
    "          hips, revolute elbows, knees and ankles, anatomical limits, joint friction),\n"
    "          dropped in a T-pose from 10 m onto a 1 m rope tied to the pelvis; reports the\n"
    "          worst cone, twist or hinge-limit violation in degrees.\n"
    "  vehicle  --count N cars of 1,200 kg (default 100), each a chassis on four wheel joints\n"
    "          (2 Hz springs, ratio 0.3, 20 kg wheels, motors at the rolling speed) driving at\n"
    "          10 m/s on the ground through the scene's own wheel-ground contacts; prints the\n"
    "          first car's bounce and ride height against what its springs and tyres promise.\n"
    "  suspension-bridge  --count N bridges (default 10) of 22 planks on revolute and ball\n"
    "          joints hung from two cables of distance joints, each crossed by a 500 kg cart\n"
    "          on wheel joints (contacts with the planks); prints the sag under the cart at\n"
    "          mid-span against the static solution, and the time to cross.\n"
    "  pyramid --base N (default 100): a single-layer wall of 1 m, 100 kg boxes in one\n"
    "          vertical plane, each row offset by half a box, on a static ground (base 100:\n"
    "          5,050 boxes); contacts from Bullet's narrow phase, timed apart from the step.\n"
    "  pile    --count N (default 1000) 1 kg boxes and spheres dropped into an open box;\n"
    "          contacts from Bullet's narrow phase.\n"
    "Joints are rigid unless --hertz gives them springs.";

bool is_recording_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  return in.read(magic, sizeof magic) && std::string(magic, sizeof magic) == "SSTEPREC";
}

void add_scene_options(CLI::App& cmd, SceneChoice& c) {
  c.chain.links = 10000;
  cmd.add_option("scene", c.scene, "the scene: chain, grid, bridge, hinge-chain, prismatic-stack, ragdoll, vehicle, "
                 "suspension-bridge, pyramid, pile or a scene file")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            if (name == "chain" || name == "grid" || name == "bridge" || is_joint_scene(name) ||
                is_talk_scene(name) || is_collision_scene(name) ||
                std::filesystem::is_regular_file(name))
              return {};
            return "'" + name +
                   "' is neither a scene (chain, grid, bridge, hinge-chain, prismatic-stack, "
                   "ragdoll, vehicle, suspension-bridge, pyramid, pile) nor a scene file";
          },
          "chain|grid|bridge|hinge-chain|prismatic-stack|ragdoll|vehicle|suspension-bridge|"
          "pyramid|pile|FILE"))
      ->capture_default_str();
  cmd.add_option("--links", c.chain.links, "chain, hinge-chain: links per chain")
      ->check(whole_in(1, 100000000))
      ->capture_default_str();
  cmd.add_option("--chains", c.chain.chains, "chain, hinge-chain: parallel chains")
      ->check(whole_in(1, 1000000))
      ->capture_default_str();
  cmd.add_option("--joint", c.joint, "chain: joint type")
      ->check(CLI::IsMember({"ball", "distance"}))
      ->capture_default_str();
  cmd.add_option("--layout", c.layout, "chain: laid out along x, or hanging down")
      ->check(CLI::IsMember({"horizontal", "hanging"}))
      ->capture_default_str();
  cmd.add_option("--end-mass", c.end_mass, "chain: the last link's mass, kg")
      ->check(finite_in(1e-6, 1e9));
  cmd.add_option("--linear-damping", c.chain.linear_damping, "chain: every link's, 1/s")
      ->check(finite_in(0.0, 1e9))
      ->capture_default_str();
  cmd.add_option("--angular-damping", c.chain.angular_damping, "chain: every link's, 1/s")
      ->check(finite_in(0.0, 1e9))
      ->capture_default_str();
  cmd.add_option("--size", c.grid.size, "grid: N x N bodies")
      ->check(whole_in(2, 100000))
      ->capture_default_str();
  cmd.add_option("--span", c.bridge.span, "bridge: links of the deck")
      ->check(whole_in(2, 100000000))
      ->capture_default_str();
  cmd.add_option("--loads", c.bridge.loads, "bridge: heavy bodies hanging from the deck")
      ->check(whole_in(0, 100000000))
      ->capture_default_str();
  cmd.add_option("--load-mass", c.bridge.load_mass, "bridge: mass of each load, kg")
      ->check(finite_in(1e-3, 1e9))
      ->capture_default_str();
  cmd.add_option("--hertz", c.hertz, "springs of this frequency, Hz, instead of rigid joints")
      ->check(finite_in(0.0, 1e9));
  cmd.add_option("--zeta", c.zeta, "the springs' damping ratio (needs --hertz)")
      ->check(finite_in(0.0, 1e9))
      ->capture_default_str();
  add_joint_scene_options(cmd, c);
  add_talk_scene_options(cmd, c);
  add_collision_scene_options(cmd, c);

  cmd.parse_complete_callback([&cmd, &c] {
    const bool named =
        c.scene == "chain" || c.scene == "grid" || c.scene == "bridge" || is_joint_scene(c.scene) ||
        is_talk_scene(c.scene) || is_collision_scene(c.scene);
    c.from_recording = !named && is_recording_file(c.scene);
    c.from_file = !named && !c.from_recording;
    const auto only_for = [&](const char* flag, const char* owner) {
      if (c.scene != owner && cmd.count(flag) > 0)
        throw CLI::ValidationError(flag,
                                   std::string("a ") + owner + " option, not for scene " + c.scene);
    };
    for (const char* flag :
         {"--joint", "--end-mass", "--layout", "--linear-damping", "--angular-damping"}) {
      only_for(flag, "chain");
    }
    if (c.scene != "hinge-chain") {
      for (const char* flag : {"--links", "--chains"}) only_for(flag, "chain");
    }
    only_for("--size", "grid");
    if (c.from_file || c.from_recording) {
      for (const char* flag : {"--hertz", "--zeta"}) {
        if (cmd.count(flag) > 0)
          throw CLI::ValidationError(flag, "not for a scene file (its joints carry their springs)");
      }
    }
    if (c.from_file) {
      // Loaded once here, so that a bad file is reported before anything runs.
      std::ifstream in(c.scene, std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      c.file_text = text.str();
      c.file_settings = load_scene_text(c.file_text, c.scene).settings();
    }
    for (const char* flag : {"--span", "--loads", "--load-mass"}) only_for(flag, "bridge");
    if (c.bridge.loads > c.bridge.span)
      throw CLI::ValidationError("--loads", "value " + std::to_string(c.bridge.loads) +
                                                ": at most --span (" +
                                                std::to_string(c.bridge.span) + ")");
    c.chain.joint = c.joint == "ball" ? scenes::ChainJoint::Ball : scenes::ChainJoint::Distance;
    c.chain.layout =
        c.layout == "hanging" ? scenes::ChainLayout::Hanging : scenes::ChainLayout::Horizontal;
    if (cmd.count("--end-mass") > 0) {
      c.chain.link_masses.assign(static_cast<std::size_t>(c.chain.links), c.chain.link_mass);
      c.chain.link_masses.back() = c.end_mass;
    }
    const bool soft = cmd.count("--hertz") > 0;
    if (!soft && cmd.count("--zeta") > 0)
      throw CLI::ValidationError("--zeta", "needs --hertz (omit both for rigid joints)");
    c.chain.spring = c.grid.spring = c.bridge.spring =
        soft ? Spring::soft(c.hertz, c.zeta) : Spring::rigid();
    c.spring_text = soft ? "spring " + format_number(c.hertz) + " Hz, zeta " + format_number(c.zeta)
                         : std::string("rigid");
    finish_joint_scene_options(cmd, c);
    finish_talk_scene_options(cmd, c);
    finish_collision_scene_options(cmd, c);
  });
  cmd.footer(kSceneHelp);
}

std::vector<Eigen::Vector3d> positions(const World& world, const std::vector<BodyId>& bodies) {
  std::vector<Eigen::Vector3d> p;
  p.reserve(bodies.size());
  for (BodyId b : bodies) p.push_back(world.body(b).position);
  return p;
}

void step_scene(World& world, const SceneRun& run, double dt) {
  if (run.contacts) world.step(dt, run.contacts());
  else world.step(dt);
}

WorldSettings scene_settings(const SceneChoice& c) {
  return c.from_file ? c.file_settings : WorldSettings{};
}

namespace {

SceneRun load_file_scene(World& world, const SceneChoice& c) {
  World loaded = load_scene_text(c.file_text, c.scene);
  loaded.set_settings(world.settings());
  world = std::move(loaded);
  return describe_world(world, "file " + c.scene);
}

}  // namespace

std::vector<BodyId> dynamic_bodies(const World& world) {
  std::vector<BodyId> dynamic;
  for (BodyId b : world.body_ids()) {
    if (world.body(b).type == BodyType::Dynamic) dynamic.push_back(b);
  }
  return dynamic;
}

SceneRun describe_world(const World& world, const std::string& name) {
  SceneRun run;
  run.joints = world.joint_ids();
  run.bodies = dynamic_bodies(world);
  Eigen::AlignedBox3d box;
  for (BodyId b : world.body_ids()) box.extend(world.body(b).position);
  // Joints per type, in the order of JointType.
  std::vector<std::pair<JointType, std::size_t>> per_type;
  for (JointId j : run.joints) {
    const JointType type = world.joint_type(j);
    auto it = std::find_if(per_type.begin(), per_type.end(),
                           [type](const auto& p) { return p.first == type; });
    if (it == per_type.end()) per_type.emplace_back(type, 1);
    else ++it->second;
  }
  std::sort(per_type.begin(), per_type.end());
  std::string joints_text;
  for (const auto& [type, n] : per_type)
    joints_text += (joints_text.empty() ? "" : ", ") + std::to_string(n) + " " +
                   joint_type_name(type);
  run.rows = static_cast<double>(world.step_plan().rows_per_pass);
  run.description = name + ": " + std::to_string(world.body_count()) + " bodies, " +
                    (joints_text.empty() ? std::string("no") : joints_text) + " joints";
  run.reach = box.isEmpty() ? 0.0 : box.diagonal().norm();
  return run;
}

SceneRun build_scene(World& world, const SceneChoice& c) {
  if (is_joint_scene(c.scene)) return build_joint_scene(world, c);
  if (is_talk_scene(c.scene)) return build_talk_scene(world, c);
  if (is_collision_scene(c.scene)) return build_collision_scene(world, c);
  if (c.from_file) return load_file_scene(world, c);
  SceneRun run;
  if (c.scene == "chain") {
    const scenes::ChainOptions& chain = c.chain;
    const scenes::ChainScene built = scenes::build_chain(world, chain);
    const std::size_t links = built.links.front().size();
    run.joints = built.joints;
    for (const auto& links_of_chain : built.links)
      run.bodies.insert(run.bodies.end(), links_of_chain.begin(), links_of_chain.end());
    run.rows = static_cast<double>(run.joints.size()) * scenes::rows_per_joint(chain.joint);
    run.description = "chain: " + std::to_string(chain.chains) + " x " + std::to_string(links) +
                      " links, " + (chain.joint == scenes::ChainJoint::Ball ? "ball" : "distance") +
                      " joints, " + c.spring_text;
    if (chain.layout == scenes::ChainLayout::Hanging) run.description += ", hanging";
    if (!chain.link_masses.empty())
      run.description += ", end mass " + format_number(chain.link_masses.back()) + " kg";
    run.reach = chain.link_spacing * static_cast<double>(links);
    run.stretch_ratio = [&world, built, rest = run.reach] {
      double worst = 0.0;
      for (std::size_t k = 0; k < built.links.size(); ++k) {
        std::vector<BodyId> path{built.anchors[k]};
        path.insert(path.end(), built.links[k].begin(), built.links[k].end());
        worst = std::max(worst, metrics::stretch_ratio(positions(world, path), rest));
      }
      return worst;
    };
  } else if (c.scene == "bridge") {
    const scenes::BridgeOptions& bridge = c.bridge;
    const scenes::BridgeScene built = scenes::build_bridge(world, bridge);
    run.joints = built.joints;
    run.bodies = built.links;
    run.bodies.insert(run.bodies.end(), built.loads.begin(), built.loads.end());
    run.rows = 3.0 * static_cast<double>(bridge.span + 1) + static_cast<double>(bridge.loads);
    run.description = "bridge: " + std::to_string(bridge.span) + " links, " +
                      std::to_string(bridge.loads) + " loads of " +
                      format_number(bridge.load_mass) + " kg, " + c.spring_text;
    run.reach = 0.25 * bridge.span + bridge.rod_length;
    run.stretch_ratio = [&world, built, span = bridge.span] {
      return metrics::stretch_ratio(positions(world, built.links), 0.25 * (span - 1));
    };
  } else {
    const scenes::GridOptions& grid = c.grid;
    const scenes::GridScene built = scenes::build_grid(world, grid);
    const auto n = static_cast<std::size_t>(grid.size);
    run.joints = built.joints;
    run.bodies.assign(built.bodies.begin() + static_cast<long>(n), built.bodies.end());
    run.rows = 3.0 * static_cast<double>(run.joints.size());
    run.description = "grid: " + std::to_string(grid.size) + " x " + std::to_string(grid.size) +
                      " bodies, ball joints, " + c.spring_text;
    run.reach = grid.spacing * static_cast<double>(n);
    run.stretch_ratio = [&world, built, n, spacing = grid.spacing] {
      double worst = 0.0;
      for (std::size_t col = 0; col < n; ++col) {
        std::vector<BodyId> column;
        for (std::size_t row = 0; row < n; ++row) column.push_back(built.bodies[row * n + col]);
        worst = std::max(worst, metrics::stretch_ratio(positions(world, column),
                                                       spacing * static_cast<double>(n - 1)));
      }
      return worst;
    };
  }
  return run;
}

}  // namespace softstep::tool
