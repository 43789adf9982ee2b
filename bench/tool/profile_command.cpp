#include "tool/profile_command.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "tool/progress_bar.hpp"
#include "tool/report_files.hpp"
#include "tool/joint_scenes.hpp"
#include "tool/scene_options.hpp"

namespace softstep::tool {

const std::string kProfileUsage =
    std::string(
        "usage: softstep profile [chain|grid|bridge|hinge-chain|prismatic-stack] [scene options]\n"
        "                        [--steps S] [--substeps N] [--iterations N] [--relax N] [--threads T]\n"
        "                        [--threads-fixed] [--simd scalar|sse|avx2]\n"
        "                        [--no-warm-start] [--no-sleep] [--general] [--plan]\n"
        "                        [--json FILE] [--csv FILE] [--trace FILE]\n") +
    kSceneUsage + "\n" + kJointSceneUsage +
    "\n  Stepped S times at 60 Hz (default 300).\n"
    "  --plan        print the step plan of the last step: effects, stages, kernel variants;\n"
    "  --threads T   at most T threads (0: all cores); each step runs on one or T, whichever ran\n"
    "                recent steps faster, and on one below 4,096 bodies and joints;\n"
    "  --threads-fixed  every step on exactly T threads (no adaptive choice);\n"
    "  --general     every joint on the general kernel and every stage run (the baseline);\n"
    "  --no-sleep    islands at rest stay awake;\n"
    "  --json FILE   the figures as one JSON object (with the plan); --csv FILE   one row per "
    "step;\n"
    "  --trace FILE  Chrome / Perfetto trace events: one slice per stage per thread.";

namespace {

// "rigid", "soft + min + max", "any (general)", "point + hinge lock + limits", ...
std::string kernel_features(const PlanKernel& k) {
  if (k.type != JointType::Ball && k.type != JointType::Distance) return k.parts;
  if (k.row == SpringRow::Any) return "general (per-lane switches)";
  std::string text = spring_row_name(k.row);
  if (k.lower_limit) text += " + min";
  if (k.upper_limit) text += " + max";
  return text;
}

void print_plan(const StepPlan& plan) {
  std::printf("plan             %s, built %llu time(s)\n",
              plan.specialized ? "specialized" : "general (--general)",
              static_cast<unsigned long long>(plan.builds));
  std::string effects;
  const auto effect = [&](bool on, const char* name) {
    if (on) effects += (effects.empty() ? "" : ", ") + std::string(name);
  };
  effect(plan.gravity, "gravity");
  effect(plan.damping, "damping");
  effect(plan.forces, "forces");
  effect(plan.springs, "springs");
  effect(plan.limits, "limits");
  effect(plan.motors, "motors");
  effect(plan.warm_start, "warm start");
  effect(plan.kinematic_bodies, "kinematic bodies");
  effect(plan.unconstrained_bodies, "bodies without joints");
  std::printf("  effects        %s\n", effects.empty() ? "none" : effects.c_str());
  std::string stages;
  for (PlanStage st : plan.stages)
    stages += (stages.empty() ? "" : " ") + std::string(plan_stage_name(st));
  std::printf("  stages         %s\n", stages.empty() ? "none" : stages.c_str());
  std::printf("  awake bodies   %zu, sleeping islands %zu, rows per pass %llu\n", plan.awake_bodies,
              plan.sleeping_islands, static_cast<unsigned long long>(plan.rows_per_pass));
  std::printf("  kernel variants (type, features: batches, joints)\n");
  for (const PlanKernel& k : plan.kernels) {
    std::printf("    %-9s %-40s %8u batches %9u joints\n", joint_type_name(k.type),
                kernel_features(k).c_str(), k.batches, k.joints);
  }
}

JsonObject plan_json(const StepPlan& plan) {
  JsonObject j;
  j.add("specialized", plan.specialized ? 1 : 0);
  std::vector<std::string> stages;
  for (PlanStage st : plan.stages) stages.emplace_back(plan_stage_name(st));
  j.add_strings("stages", stages);
  JsonObject effects;
  effects.add("gravity", plan.gravity);
  effects.add("damping", plan.damping);
  effects.add("forces", plan.forces);
  effects.add("springs", plan.springs);
  effects.add("limits", plan.limits);
  effects.add("warm_start", plan.warm_start);
  effects.add("kinematic_bodies", plan.kinematic_bodies);
  effects.add("unconstrained_bodies", plan.unconstrained_bodies);
  j.add_object("effects", effects);
  std::vector<JsonObject> kernels;
  for (const PlanKernel& k : plan.kernels) {
    JsonObject o;
    o.add_string("type", joint_type_name(k.type));
    o.add_string("spring_row", spring_row_name(k.row));
    o.add("lower_limit", k.lower_limit);
    o.add("upper_limit", k.upper_limit);
    o.add_string("parts", k.parts);
    o.add("rows_per_joint", k.rows_per_joint);
    o.add("batches", k.batches);
    o.add("joints", k.joints);
    kernels.push_back(o);
  }
  j.add_objects("kernels", kernels);
  j.add("rows_per_pass", static_cast<double>(plan.rows_per_pass));
  return j;
}

struct CsvRow {
  double ms;
  std::array<double, kStageCount> stages;
};

}  // namespace

int profile_command(Arguments& args) {
  const SceneChoice choice = take_scene_options(args);
  const long steps = args.take_int("--steps", 300, 1, 100000000);
  WorldSettings settings;
  settings.substeps = static_cast<int>(args.take_int("--substeps", 4, 1, 1000));
  settings.solve_iterations = static_cast<int>(args.take_int("--iterations", 1, 1, 1000));
  settings.relax_iterations = static_cast<int>(args.take_int("--relax", 1, 0, 1000));
  settings.threads = static_cast<int>(args.take_int("--threads", 0, 0, 256));  // 0: all cores
  settings.fixed_threads = args.take_switch("--threads-fixed");
  settings.simd = parse_simd(args.take_choice("--simd", {"best", "scalar", "sse", "avx2"}, "best"));
  settings.warm_start = !args.take_switch("--no-warm-start");
  settings.sleeping = !args.take_switch("--no-sleep");
  settings.specialize = !args.take_switch("--general");
  const bool show_plan = args.take_switch("--plan");
  const std::string json_path = args.take_string("--json", "");
  const std::string csv_path = args.take_string("--csv", "");
  const std::string trace_path = args.take_string("--trace", "");
  args.reject_leftovers();
  check_writable_file("--json", json_path);
  check_writable_file("--csv", csv_path);
  check_writable_file("--trace", trace_path);
  std::vector<CsvRow> csv_rows;

  World world(settings);
  world.set_profiling(true);
  const SceneRun run = build_scene(world, choice);

  const double dt = 1.0 / 60.0;
  std::vector<double> step_ms;
  std::vector<std::array<double, kStageCount>> stage_ms;
  std::vector<double> wait_share;
  Trace trace;
  double worst_error_run = 0.0;
  const long error_every = std::max(1L, steps / 100);  // ~100 samples, outside the timed step
  const auto run_start = std::chrono::steady_clock::now();
  {
    ProgressBar bar("profile", steps);
    for (long i = 0; i < steps; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      world.step(dt);
      const auto t1 = std::chrono::steady_clock::now();
      step_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      const StepProfile& p = world.last_step_profile();
      stage_ms.push_back(p.stage_ms);
      double waited = 0.0;
      for (double w : p.barrier_wait_ms) waited += w;
      wait_share.push_back(p.step_ms > 0.0 ? waited / (p.step_ms * p.threads) : 0.0);
      if (!trace_path.empty()) {
        trace.add_step(std::chrono::duration<double, std::micro>(t0 - run_start).count(), p);
      }
      if (i % error_every == 0 || i + 1 == steps) {
        worst_error_run = std::max(worst_error_run, scenes::joint_errors(world, run.joints).max);
      }
      if (!csv_path.empty()) csv_rows.push_back({step_ms.back(), p.stage_ms});
      bar.update(i + 1);
    }
  }
  const scenes::JointErrors errors = scenes::joint_errors(world, run.joints);
  const SolverLayout layout = world.solver_layout();
  const double ms = median(step_ms);
  // Each sub-step solves every row `iterations` times and relaxes it `relax` times, unless
  // the plan runs no relax pass (springs only: springs are not relaxed).
  const std::vector<PlanStage>& planned = world.step_plan().stages;
  const bool relaxed = std::find(planned.begin(), planned.end(), PlanStage::Relax) != planned.end();
  const double row_solves = run.rows * settings.substeps *
                            (settings.solve_iterations + (relaxed ? settings.relax_iterations : 0));
  std::array<double, kStageCount> stage_median{};
  for (int k = 0; k < kStageCount; ++k) {
    std::vector<double> v;
    for (const auto& s : stage_ms) v.push_back(s[static_cast<std::size_t>(k)]);
    stage_median[static_cast<std::size_t>(k)] = median(v);
  }
  const double stretch = run.stretch_ratio();

  std::printf("scene            %s\n", run.description.c_str());
  std::printf("bodies / joints  %zu / %zu (%.0f constraint rows)\n", world.body_count(),
              world.joint_count(), run.rows);
  std::printf(
      "settings         %ld steps of 1/60 s, %d sub-steps, %d solve + %d relax iterations, %d "
      "thread(s), simd %s (%d lanes)%s\n",
      steps, settings.substeps, settings.solve_iterations, settings.relax_iterations,
      world.last_step_profile().threads, simd_width_name(layout.simd), layout.lanes,
      settings.warm_start ? "" : ", no warm start");
  std::string per_color;
  for (std::uint32_t n : layout.joints_per_color)
    per_color += (per_color.empty() ? "" : " ") + std::to_string(n);
  std::printf("colors           %d used (joints per color: %s), overflow %u, lane fill %.3f\n",
              layout.colors_used, per_color.c_str(), layout.overflow_joints, layout.lane_fill);
  std::printf("awake bodies     %zu, sleeping islands %zu\n", world.step_plan().awake_bodies,
              world.step_plan().sleeping_islands);
  if (show_plan) {
    std::printf("\n");
    print_plan(world.step_plan());
  }
  std::printf("\n  stage                  ms/step   share\n");
  for (int k = 0; k < kStageCount; ++k) {
    const double v = stage_median[static_cast<std::size_t>(k)];
    std::printf("  %-22s %8.3f  %5.1f %%\n", stage_name(static_cast<Stage>(k)), v,
                ms > 0 ? 100.0 * v / ms : 0.0);
  }
  std::printf("  %-22s %8.3f  (median of %ld steps)\n\n", "step", ms, steps);
  std::printf("row solves / s   %.3g (ns per row solve %.2f)\n", row_solves / (ms * 1e-3),
              ms * 1e6 / row_solves);
  std::printf("barrier wait     %.1f %% of thread time\n", 100.0 * median(wait_share));
  std::printf(
      "joint error      max %.6g m, rms %.6g m after the last step; worst over the run %.6g m\n",
      errors.max, errors.rms, worst_error_run);
  std::printf(
      "stretch ratio    %.6g (path length through the bodies / rest length, worst chain or "
      "column)\n",
      stretch);
  std::printf("state hash       %016llx\n", static_cast<unsigned long long>(world.state_hash()));

  if (!json_path.empty()) {
    JsonObject j;
    j.add_string("scene", choice.scene);
    j.add_string("description", run.description);
    j.add("bodies", static_cast<double>(world.body_count()));
    j.add("joints", static_cast<double>(world.joint_count()));
    j.add("steps", static_cast<double>(steps));
    j.add("substeps", settings.substeps);
    j.add("solve_iterations", settings.solve_iterations);
    j.add("relax_iterations", settings.relax_iterations);
    j.add("threads", world.last_step_profile().threads);
    j.add_string("simd", simd_width_name(layout.simd));
    j.add("ms_per_step", ms);
    JsonObject stages;
    for (int k = 0; k < kStageCount; ++k)
      stages.add(stage_name(static_cast<Stage>(k)), stage_median[static_cast<std::size_t>(k)]);
    j.add_object("stage_ms", stages);
    j.add("rows_per_second", row_solves / (ms * 1e-3));
    j.add("barrier_wait_share", median(wait_share));
    j.add("colors", layout.colors_used);
    j.add("overflow_joints", static_cast<double>(layout.overflow_joints));
    j.add("max_joint_error_m", errors.max);
    j.add("rms_joint_error_m", errors.rms);
    j.add("max_joint_error_run_m", worst_error_run);
    j.add("stretch_ratio", stretch);
    j.add_object("plan", plan_json(world.step_plan()));
    j.add("awake_bodies", static_cast<double>(world.step_plan().awake_bodies));
    j.add("sleeping_islands", static_cast<double>(world.step_plan().sleeping_islands));
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx",
                  static_cast<unsigned long long>(world.state_hash()));
    j.add_string("state_hash", hash);
    write_file(json_path, j.text() + "\n");
  }
  if (!csv_path.empty()) {
    std::string csv = "step,ms";
    for (int k = 0; k < kStageCount; ++k)
      csv += std::string(",") + stage_name(static_cast<Stage>(k)) + "_ms";
    csv += "\n";
    for (std::size_t i = 0; i < csv_rows.size(); ++i) {
      csv += std::to_string(i) + "," + format_number(csv_rows[i].ms);
      for (double v : csv_rows[i].stages) csv += "," + format_number(v);
      csv += "\n";
    }
    write_file(csv_path, csv);
  }
  if (!trace_path.empty()) write_file(trace_path, trace.text());
  return 0;
}

}  // namespace softstep::tool
