#include "tool/joint_scenes.hpp"

#include <algorithm>
#include <numbers>

#include <CLI/CLI.hpp>

#include "softstep/metrics.hpp"
#include "tool/arguments.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

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
  return scene == "hinge-chain" || scene == "prismatic-stack" || scene == "ragdoll";
}

void add_joint_scene_options(CLI::App& cmd, SceneChoice& c) {
  cmd.add_option("--limit", c.hinge_limit_deg, "hinge-chain: every hinge within +-DEG, degrees")
      ->check(finite_in(0.0, 1e6));
  cmd.add_option("--motor-torque", c.hinge.motor.max_torque,
                 "hinge-chain: a motor of at most NM N m on every hinge")
      ->check(finite_in(0.0, 1e9));
  cmd.add_option("--motor-speed", c.hinge.motor.speed,
                 "hinge-chain: the motor's speed, rad/s (default 0: joint friction)")
      ->check(finite_in(-1e3, 1e3));
  c.stack.columns = 1000;
  c.stack.height = 10;
  cmd.add_option("--columns", c.stack.columns, "prismatic-stack: columns")
      ->check(whole_in(1, 10000000))
      ->capture_default_str();
  cmd.add_option("--height", c.stack.height, "prismatic-stack: cubes per column")
      ->check(whole_in(1, 10000000))
      ->capture_default_str();
}

void finish_joint_scene_options(const CLI::App& cmd, SceneChoice& c) {
  const auto only_for = [&](const char* flag, const char* owner) {
    if (c.scene != owner && cmd.count(flag) > 0)
      throw CLI::ValidationError(flag, std::string("a ") + owner + " option, not for scene " + c.scene);
  };
  for (const char* flag : {"--limit", "--motor-torque", "--motor-speed"}) only_for(flag, "hinge-chain");
  for (const char* flag : {"--columns", "--height"}) only_for(flag, "prismatic-stack");
  c.hinge.links = c.chain.links;
  c.hinge.chains = c.chain.chains;
  if (cmd.count("--limit") > 0) {
    const double rad = c.hinge_limit_deg * std::numbers::pi / 180.0;
    c.hinge.limit = {true, -rad, rad};
  }
  c.hinge.motor.enabled = cmd.count("--motor-torque") > 0;
  if (!c.chain.spring.is_rigid()) {
    c.hinge.spring.spring = c.chain.spring;
    c.stack.spring.spring = c.chain.spring;
  }
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
  } else if (c.scene == "ragdoll") {
    const scenes::RagdollScene built = scenes::build_ragdolls(world, c.ragdoll);
    for (const scenes::Ragdoll& r : built.ragdolls) {
      run.bodies.insert(run.bodies.end(), r.bodies.begin(), r.bodies.end());
      run.joints.insert(run.joints.end(), r.swing_twists.begin(), r.swing_twists.end());
      run.joints.insert(run.joints.end(), r.hinges.begin(), r.hinges.end());
    }
    run.joints.insert(run.joints.end(), built.ropes.begin(), built.ropes.end());
    run.description = "ragdoll: " + std::to_string(c.ragdoll.count) +
                      " ragdolls of 16 bodies, 9 swing-twist + 6 revolute joints each, on ropes";
    run.reach = c.ragdoll.rope_length + 1.0;  // the rope, and the legs below the pelvis
    run.limit_violation_deg = [&world, built] {
      return scenes::ragdoll_limit_violation(world, built).worst();
    };
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
