#include "tool/joint_scenes.hpp"

#include <algorithm>
#include <numbers>

#include "softstep/metrics.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

const char* const kJointSceneUsage =
    "  hinge-chain [--links N] [--chains M] [--limit DEG] [--motor-torque NM [--motor-speed W]]\n"
    "      N box links (1 kg, 0.25 x 0.05 x 0.05 m) on revolute joints about z, laid out along\n"
    "      x and swinging down; --limit: every hinge within +-DEG; --motor-torque: a motor of\n"
    "      at most NM N m driving at W rad/s (default 0: joint friction); --hertz: torsion\n"
    "      springs towards straight.\n"
    "  prismatic-stack [--columns N] [--height H]   (default 1000 columns of 10)\n"
    "      H 1 kg cubes per column, each on a vertical slider to the one below, on springs of\n"
    "      4 Hz (or --hertz) within -0.2 .. +0.1 m of their 0.5 m spacing.";

namespace {

// The worst stretch ratio over the paths static start k, bodies[k]...
std::function<double()> worst_stretch(const World& world, std::vector<BodyId> starts,
                                      std::vector<std::vector<BodyId>> bodies, double rest) {
  return [&world, starts = std::move(starts), bodies = std::move(bodies), rest] {
    double worst = 0.0;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      std::vector<BodyId> path{starts[k]};
      path.insert(path.end(), bodies[k].begin(), bodies[k].end());
      worst = std::max(worst, metrics::stretch_ratio(positions(world, path), rest));
    }
    return worst;
  };
}

}  // namespace

bool is_joint_scene(const std::string& scene) {
  return scene == "hinge-chain" || scene == "prismatic-stack";
}

void take_joint_scene_options(Arguments& args, SceneChoice& c) {
  for (const char* flag : {"--limit", "--motor-torque", "--motor-speed"}) {
    if (c.scene != "hinge-chain" && args.has(flag))
      throw UsageError(std::string(flag) + " is a hinge-chain option");
  }
  for (const char* flag : {"--columns", "--height"}) {
    if (c.scene != "prismatic-stack" && args.has(flag))
      throw UsageError(std::string(flag) + " is a prismatic-stack option");
  }
  c.hinge.links = c.chain.links;
  c.hinge.chains = c.chain.chains;
  if (args.has("--limit")) {
    const double rad = args.take_double("--limit", 0.0, 0.0, 1e6) * std::numbers::pi / 180.0;
    c.hinge.limit = {true, -rad, rad};
  }
  if (args.has("--motor-torque")) {
    c.hinge.motor.enabled = true;
    c.hinge.motor.max_torque = args.take_double("--motor-torque", 0.0, 0.0, 1e9);
  }
  c.hinge.motor.speed = args.take_double("--motor-speed", 0.0, -1e3, 1e3);
  if (!c.chain.spring.is_rigid()) {
    c.hinge.spring.spring = c.chain.spring;
    c.stack.spring.spring = c.chain.spring;
  }
  c.stack.columns = static_cast<int>(args.take_int("--columns", 1000, 1, 10000000));
  c.stack.height = static_cast<int>(args.take_int("--height", 10, 1, 10000000));
}

SceneRun build_joint_scene(World& world, const SceneChoice& c) {
  SceneRun run;
  if (c.scene == "hinge-chain") {
    const scenes::HingeChainOptions& o = c.hinge;
    const scenes::HingeChainScene built = scenes::build_hinge_chain(world, o);
    run.joints = built.joints;
    for (const auto& links : built.links) run.bodies.insert(run.bodies.end(), links.begin(), links.end());
    run.description = "hinge-chain: " + std::to_string(o.chains) + " x " +
                      std::to_string(o.links) + " links, revolute joints";
    if (o.limit.enabled)
      run.description += ", limit +-" + format_number(o.limit.upper * 180.0 / std::numbers::pi) + " deg";
    if (o.motor.enabled) {
      run.description += ", motor " + format_number(o.motor.speed) + " rad/s, " +
                         format_number(o.motor.max_torque) + " N m";
    }
    run.description += o.spring.spring.is_free() ? ", no spring" : ", " + c.spring_text;
    run.reach = o.link_spacing * o.links;
    run.stretch_ratio = worst_stretch(world, built.anchors, built.links, run.reach);
  } else {
    const scenes::PrismaticStackOptions& o = c.stack;
    const scenes::PrismaticStackScene built = scenes::build_prismatic_stack(world, o);
    run.joints = built.joints;
    for (const auto& column : built.columns) run.bodies.insert(run.bodies.end(), column.begin(), column.end());
    run.description = "prismatic-stack: " + std::to_string(o.columns) + " columns of " +
                      std::to_string(o.height) + ", sliders on springs of " +
                      format_number(o.spring.spring.hertz) + " Hz with limits";
    run.reach = o.spacing * o.height;
    run.stretch_ratio = worst_stretch(world, built.grounds, built.columns, run.reach);
  }
  // Rows as the plan counts them: each type's parts plus the limit, motor and spring rows
  // its joints switch on.
  run.rows = static_cast<double>(world.step_plan().rows_per_pass);
  return run;
}

}  // namespace softstep::tool
