#include "tool/scene_options.hpp"

#include <algorithm>

#include "softstep/metrics.hpp"
#include "tool/joint_scenes.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

const char* const kSceneUsage =
    "  chain [--links N] [--chains M] [--joint ball|distance] [--end-mass KG]\n"
    "        [--layout horizontal|hanging]   (default: chain, 10000 links)\n"
    "      N solid 1 kg spheres of radius 0.1 m, 0.25 m apart, laid out horizontally (or\n"
    "      hanging straight down, unstretched), the first link jointed to the static world;\n"
    "      M parallel chains 1 m apart. --end-mass: the last link weighs KG instead (a\n"
    "      mass-ratio chain).\n"
    "  grid [--size N]   (default 100)\n"
    "      N x N spheres of radius 0.4 m, 1000 kg/m^3, 1 m apart in a vertical plane, top row\n"
    "      static, ball joints to the right and lower neighbours.\n"
    "  bridge [--span N] [--loads K] [--load-mass M]   (default 1000 links, 10 loads of 50 kg)\n"
    "      a chain of N links pinned at both ends, K heavy bodies hanging from it on 0.5 m rods.\n"
    "  --hertz F [--zeta Z]   springs of F Hz and damping ratio Z (default 0.7) instead of\n"
    "      rigid joints.";

SceneChoice take_scene_options(Arguments& args) {
  SceneChoice c;
  const std::vector<std::string> positionals = args.take_positionals();
  c.scene = positionals.empty() ? "chain" : positionals.front();
  if (positionals.size() > 1 || (c.scene != "chain" && c.scene != "grid" && c.scene != "bridge" &&
                                  !is_joint_scene(c.scene))) {
    throw UsageError("unknown scene '" + positionals.back() +
                     "' (scenes: chain, grid, bridge, hinge-chain, prismatic-stack)");
  }
  const auto only_for = [&](const char* flag, const char* owner) {
    if (c.scene != owner && args.has(flag))
      throw UsageError(std::string(flag) + " is a " + owner + " option");
  };
  for (const char* flag : {"--joint", "--end-mass", "--layout"}) only_for(flag, "chain");
  if (c.scene != "hinge-chain") {
    for (const char* flag : {"--links", "--chains"}) only_for(flag, "chain");
  }
  only_for("--size", "grid");
  for (const char* flag : {"--span", "--loads", "--load-mass"}) only_for(flag, "bridge");

  c.chain.links = static_cast<int>(args.take_int("--links", 10000, 1, 100000000));
  c.chain.chains = static_cast<int>(args.take_int("--chains", 1, 1, 1000000));
  c.chain.joint = args.take_choice("--joint", {"ball", "distance"}, "ball") == "ball"
                      ? scenes::ChainJoint::Ball
                      : scenes::ChainJoint::Distance;
  c.chain.layout =
      args.take_choice("--layout", {"horizontal", "hanging"}, "horizontal") == "hanging"
          ? scenes::ChainLayout::Hanging
          : scenes::ChainLayout::Horizontal;
  if (args.has("--end-mass")) {
    c.chain.link_masses.assign(static_cast<std::size_t>(c.chain.links), c.chain.link_mass);
    c.chain.link_masses.back() = args.take_double("--end-mass", 1.0, 1e-6, 1e9);
  }
  c.grid.size = static_cast<int>(args.take_int("--size", 100, 2, 100000));
  c.bridge.span = static_cast<int>(args.take_int("--span", 1000, 2, 100000000));
  c.bridge.loads = static_cast<int>(args.take_int("--loads", 10, 0, c.bridge.span));
  c.bridge.load_mass = args.take_double("--load-mass", 50.0, 1e-3, 1e9);
  const bool soft = args.has("--hertz");
  // Checked before take_double consumes --zeta (has() sees only flags not yet taken).
  if (!soft && args.has("--zeta"))
    throw UsageError("--zeta needs --hertz (omit both for rigid joints)");
  const double hertz = args.take_double("--hertz", 0.0, 0.0, 1e9);
  const double zeta = args.take_double("--zeta", soft ? 0.7 : 0.0, 0.0, 1e9);
  c.chain.spring = c.grid.spring = c.bridge.spring =
      soft ? Spring::soft(hertz, zeta) : Spring::rigid();
  c.spring_text = soft ? "spring " + format_number(hertz) + " Hz, zeta " + format_number(zeta)
                       : std::string("rigid");
  take_joint_scene_options(args, c);
  return c;
}

std::vector<Eigen::Vector3d> positions(const World& world, const std::vector<BodyId>& bodies) {
  std::vector<Eigen::Vector3d> p;
  p.reserve(bodies.size());
  for (BodyId b : bodies) p.push_back(world.body(b).position);
  return p;
}

SceneRun build_scene(World& world, const SceneChoice& c) {
  if (is_joint_scene(c.scene)) return build_joint_scene(world, c);
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
