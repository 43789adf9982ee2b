#include "tool/profile_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "scenes/chain_scene.hpp"
#include "scenes/grid_scene.hpp"
#include "tool/progress_bar.hpp"

namespace softstep::tool {

const char* const kProfileUsage =
    "usage: softstep profile [chain|grid] [scene options] [--hertz F --zeta Z] [--steps S]\n"
    "                        [--substeps N] [--relax N] [--threads T] [--simd scalar|sse|avx2]\n"
    "                        [--no-warm-start]\n"
    "  chain [--links N] [--chains M] [--joint ball|distance]   (default: chain, 10000 links)\n"
    "      N solid 1 kg spheres of radius 0.1 m, 0.25 m apart, laid out horizontally, the\n"
    "      first link jointed to the static world; M parallel chains 1 m apart.\n"
    "  grid [--size N]   (default 100)\n"
    "      N x N spheres of radius 0.4 m, 1000 kg/m^3, 1 m apart in a vertical plane, top row\n"
    "      static, ball joints to the right and lower neighbours.\n"
    "  Stepped S times at 60 Hz (default 300). Rigid joints unless --hertz is given.";

namespace {

SimdWidth parse_simd(const std::string& s) {
  if (s == "scalar") return SimdWidth::Scalar;
  if (s == "sse") return SimdWidth::Sse;
  if (s == "avx2") return SimdWidth::Avx2;
  return SimdWidth::Best;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

namespace {

// A built scene: what the report needs to know about it.
struct SceneRun {
  std::string description;
  std::vector<JointId> joints;
  double rows = 0.0;
};

}  // namespace

int profile_command(Arguments& args) {
  const std::vector<std::string> positionals = args.take_positionals();
  const std::string scene = positionals.empty() ? "chain" : positionals.front();
  if (positionals.size() > 1 || (scene != "chain" && scene != "grid")) {
    throw UsageError("unknown scene '" + positionals.back() + "' (scenes: chain, grid)");
  }
  const auto only_for = [&](const char* flag, const char* owner) {
    if (scene != owner && args.has(flag))
      throw UsageError(std::string(flag) + " is a " + owner + " option");
  };
  for (const char* flag : {"--links", "--chains", "--joint"}) only_for(flag, "chain");
  only_for("--size", "grid");

  scenes::ChainOptions chain;
  chain.links = static_cast<int>(args.take_int("--links", 10000, 1, 100000000));
  chain.chains = static_cast<int>(args.take_int("--chains", 1, 1, 1000000));
  chain.joint = args.take_choice("--joint", {"ball", "distance"}, "ball") == "ball"
                    ? scenes::ChainJoint::Ball
                    : scenes::ChainJoint::Distance;
  scenes::GridOptions grid;
  grid.size = static_cast<int>(args.take_int("--size", 100, 2, 100000));
  const bool soft = args.has("--hertz");
  const double hertz = args.take_double("--hertz", 0.0, 0.0, 1e9);
  const double zeta = args.take_double("--zeta", soft ? 0.7 : 0.0, 0.0, 1e9);
  if (!soft && args.has("--zeta"))
    throw UsageError("--zeta needs --hertz (omit both for rigid joints)");
  chain.spring = grid.spring = soft ? Spring::soft(hertz, zeta) : Spring::rigid();
  const long steps = args.take_int("--steps", 300, 1, 100000000);
  WorldSettings settings;
  settings.substeps = static_cast<int>(args.take_int("--substeps", 4, 1, 1000));
  settings.relax_iterations = static_cast<int>(args.take_int("--relax", 1, 0, 1000));
  settings.threads = static_cast<int>(args.take_int("--threads", 1, 1, 256));
  settings.simd = parse_simd(args.take_choice("--simd", {"best", "scalar", "sse", "avx2"}, "best"));
  settings.warm_start = !args.take_switch("--no-warm-start");
  args.reject_leftovers();

  World world(settings);
  SceneRun run;
  const std::string spring_text =
      soft ? "spring " + std::to_string(hertz) + " Hz, zeta " + std::to_string(zeta)
           : std::string("rigid");
  if (scene == "chain") {
    run.joints = scenes::build_chain(world, chain).joints;
    run.rows = static_cast<double>(run.joints.size()) * scenes::rows_per_joint(chain.joint);
    run.description = "chain: " + std::to_string(chain.chains) + " x " +
                      std::to_string(chain.links) + " links, " +
                      (chain.joint == scenes::ChainJoint::Ball ? "ball" : "distance") +
                      " joints, " + spring_text;
  } else {
    run.joints = scenes::build_grid(world, grid).joints;
    run.rows = 3.0 * static_cast<double>(run.joints.size());
    run.description = "grid: " + std::to_string(grid.size) + " x " + std::to_string(grid.size) +
                      " bodies, ball joints, " + spring_text;
  }
  const double dt = 1.0 / 60.0;
  std::vector<double> step_ms;
  step_ms.reserve(static_cast<std::size_t>(steps));
  double worst_error = 0.0;
  {
    ProgressBar bar("profile", steps);
    for (long i = 0; i < steps; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      world.step(dt);
      const auto t1 = std::chrono::steady_clock::now();
      step_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      bar.update(i + 1);
    }
  }
  const scenes::JointErrors errors = scenes::joint_errors(world, run.joints);
  worst_error = errors.max;
  const SolverLayout layout = world.solver_layout();
  const double ms = median(step_ms);
  const double rows = run.rows;
  // Each sub-step solves every row once and relaxes it `relax` times.
  const double row_solves = rows * settings.substeps * (1 + settings.relax_iterations);

  std::printf(
      "scene            chain: %d x %d links, %s joints, %s\n", chain.chains, chain.links,
      chain.joint == scenes::ChainJoint::Ball ? "ball" : "distance",
      soft ? ("spring " + std::to_string(hertz) + " Hz, zeta " + std::to_string(zeta)).c_str()
           : "rigid");
  std::printf("bodies / joints  %zu / %zu (%.0f constraint rows)\n", world.body_count(),
              world.joint_count(), rows);
  std::printf(
      "settings         %ld steps of 1/60 s, %d sub-steps, %d relax, %d thread(s), simd %s (%d "
      "lanes)%s\n",
      steps, settings.substeps, settings.relax_iterations, settings.threads,
      simd_width_name(layout.simd), layout.lanes, settings.warm_start ? "" : ", no warm start");
  std::string per_color;
  for (std::uint32_t n : layout.joints_per_color)
    per_color += (per_color.empty() ? "" : " ") + std::to_string(n);
  std::printf("colors           %d used (joints per color: %s), overflow %u, lane fill %.3f\n",
              layout.colors_used, per_color.c_str(), layout.overflow_joints, layout.lane_fill);
  std::printf("ms per step      %.3f (median of %ld)\n", ms, steps);
  std::printf("row solves / s   %.3g (ns per row solve %.2f)\n", row_solves / (ms * 1e-3),
              ms * 1e6 / row_solves);
  std::printf("joint error      max %.6g m, rms %.6g m (after the last step)\n", worst_error,
              errors.rms);
  return 0;
}

}  // namespace softstep::tool
