#include "tool/profile_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "softstep/scene_file.hpp"
#include "tool/contact_report.hpp"
#include "tool/elapsed_ms.hpp"
#include "tool/plan_report.hpp"
#include "tool/profile_recording.hpp"
#include "tool/progress_bar.hpp"
#include "tool/recording_overhead.hpp"
#include "tool/report_files.hpp"
#include "tool/scene_options.hpp"
#include "tool/traffic_report.hpp"

namespace softstep::tool {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double microseconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

}  // namespace

CLI::App* add_profile_command(CLI::App& app, ProfileOptions& o) {
  CLI::App* cmd = app.add_subcommand("profile", "run a scene and report where its step time goes");
  add_scene_options(*cmd, o.scene);
  cmd->add_option("--steps", o.steps, "steps of 1/60 s")
      ->check(whole_in(1, 100000000))
      ->capture_default_str();
  cmd->add_option("--substeps", o.settings.substeps, "sub-steps per step")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--iterations", o.settings.solve_iterations, "solve passes per sub-step")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--relax", o.settings.relax_iterations, "relax passes per sub-step")
      ->check(whole_in(0, 1000))
      ->capture_default_str();
  cmd->add_option("--threads", o.settings.threads, "threads (0: all cores)")
      ->check(whole_in(0, 256))
      ->capture_default_str();
  cmd->add_flag("--threads-fixed", o.threads_fixed,
                "every step on exactly --threads threads (no adaptive choice)");
  cmd->add_option("--simd", o.simd, "SIMD width")
      ->check(CLI::IsMember(simd_names()))
      ->capture_default_str();
  cmd->add_option("--solver", o.solver,
                  "iterative, or exact for islands whose joints form a tree (direct-for-trees, "
                  "auto)")
      ->check(CLI::IsMember(solver_names()))
      ->capture_default_str();
  cmd->add_flag("--no-warm-start", o.no_warm_start, "start every sub-step's impulses at zero");
  cmd->add_flag("--no-friction-while-solving", o.no_friction_while_solving,
                "contacts: friction rows in the relax passes only "
                "(ContactSettings::friction_while_solving = false)");
  cmd->add_flag("--no-sleep", o.no_sleep, "islands at rest stay awake");
  cmd->add_flag("--general", o.general,
                "every joint on the general kernel and every stage run (the baseline)");
  cmd->add_flag("--plan", o.show_plan,
                "print the step plan of the last step: effects, stages, kernel variants");
  cmd->add_option("--json", o.json_path, "write the figures as one JSON object (with the plan)")
      ->type_name("FILE");
  cmd->add_option("--csv", o.csv_path, "write one row per step")->type_name("FILE");
  cmd->add_option("--bandwidth", o.bandwidth_gbps,
                  "this machine's triad bandwidth (softstep_bandwidth_bench): the memory "
                  "section then shows the fraction of the bound each stage reached")
      ->type_name("GB/S")
      ->check(CLI::Range(0.001, 1e6));
  cmd->add_option("--save", o.save_path,
                  "write the scene as built (before the first step) as a scene file")
      ->type_name("FILE");
  cmd->add_option("--record", o.record_path,
                  "record the run (softstep replay FILE checks it step by step)")
      ->type_name("FILE");
  cmd->add_option("--recording-overhead", o.recording_overhead_path,
                  "measure what recording costs: a twin of the world records to FILE while the "
                  "world does not, both stepped alternately with the same contacts; prints the "
                  "step() calls' medians and their per-step ratio")
      ->type_name("FILE")
      ->excludes("--record");
  cmd->add_option("--trace", o.trace_path,
                  "write Chrome / Perfetto trace events: one slice per stage per thread")
      ->type_name("FILE");
  o.command = cmd;
  return cmd;
}

int profile_command(ProfileOptions o) {
  if (o.scene.from_recording) return profile_recording(o);
  const SceneChoice& choice = o.scene;
  const long steps = o.steps;
  // A scene file's settings, overridden by the solver options given (built-in scenes start
  // from the defaults, which the options' defaults equal).
  WorldSettings settings = scene_settings(choice);
  const auto given = [&](const char* option) {
    return o.command == nullptr || o.command->count(option) > 0;
  };
  if (given("--substeps")) settings.substeps = o.settings.substeps;
  if (given("--iterations")) settings.solve_iterations = o.settings.solve_iterations;
  if (given("--relax")) settings.relax_iterations = o.settings.relax_iterations;
  if (given("--threads")) settings.threads = o.settings.threads;
  if (o.threads_fixed) settings.fixed_threads = true;
  if (given("--simd")) settings.simd = parse_simd(o.simd);
  if (given("--solver")) settings.solver = parse_solver(o.solver);
  if (o.no_warm_start) settings.warm_start = false;
  if (o.no_friction_while_solving) settings.contact.friction_while_solving = false;
  if (o.no_sleep) settings.sleeping = false;
  if (o.general) settings.specialize = false;
  const bool show_plan = o.show_plan;
  const std::string& json_path = o.json_path;
  const std::string& csv_path = o.csv_path;
  const std::string& trace_path = o.trace_path;
  // Every output path is checked before the run (a long run must not end in a write error).
  check_writable_file("--json", json_path);
  check_writable_file("--csv", csv_path);
  check_writable_file("--trace", trace_path);
  check_writable_file("--save", o.save_path);
  check_writable_file("--record", o.record_path);
  check_writable_file("--recording-overhead", o.recording_overhead_path);

  World world(settings);
  const SceneRun run = build_scene(world, choice);
  world.set_profiling(true);
  if (!o.save_path.empty()) save_scene(world, o.save_path);
  if (!o.record_path.empty()) world.start_recording(o.record_path);
  std::optional<RecordingTwin> twin;
  if (!o.recording_overhead_path.empty()) twin.emplace(world, o.recording_overhead_path);

  const double dt = 1.0 / 60.0;
  StepSamples samples;
  // The scene's contacts, and its narrow phase (vehicle, suspension-bridge: its own; pyramid,
  // pile: Bullet's) timed apart from the step, as a user's collision detection is.
  ContactSamples contact_samples;
  std::vector<double> contact_load_ms;  // per step, for the CSV
  samples.tracing = !trace_path.empty();
  double worst_error_run = 0.0, worst_limit_run = 0.0;
  const long error_every = std::max(1L, steps / 100);  // ~100 samples, outside the timed step
  const auto run_start = std::chrono::steady_clock::now();
  {
    ProgressBar bar("profile", steps);
    for (long i = 0; i < steps; ++i) {
      std::span<const ContactManifold> contacts;
      ContactRows rows{kNaN, kNaN};
      if (run.contacts) {
        const auto c0 = std::chrono::steady_clock::now();
        contacts = run.contacts();
        const double collision_ms = elapsed_ms(c0);
        contact_samples.collision_ms.push_back(collision_ms);
        if (samples.tracing)
          samples.trace.add_slice("collision", 0, microseconds(c0 - run_start),
                                  collision_ms * 1e3);
        rows = contact_rows(world, contacts);
      }
      const bool twin_first = twin && RecordingTwin::goes_first(i);
      if (twin_first) twin->step(dt, contacts, bool(run.contacts));
      const auto t0 = std::chrono::steady_clock::now();
      if (run.contacts) world.step(dt, contacts);
      else world.step(dt);
      const auto t1 = std::chrono::steady_clock::now();
      if (twin && !twin_first) twin->step(dt, contacts, bool(run.contacts));
      const StepProfile& profile = world.last_step_profile();
      const double call_start_us = microseconds(t0 - run_start);
      if (run.contacts) {
        contact_samples.add_step(world, rows);
        contact_load_ms.push_back(profile.contact_load_ms);
        if (samples.tracing) {
          const double checks_us = call_start_us + profile.check_start_ms * 1e3;
          samples.trace.add_slice("contact_checks", 0, checks_us, profile.contact_check_ms * 1e3);
          // Beside the checks, on their second thread; otherwise just before the stages.
          const bool beside = profile.contact_load_beside_checks;
          const double load_us =
              beside ? checks_us
                     : call_start_us + (profile.team_start_ms - profile.contact_load_ms) * 1e3;
          samples.trace.add_slice("contact_load", beside ? 1 : 0, load_us,
                                  profile.contact_load_ms * 1e3);
        }
      }
      // The stages count from the threads' start.
      samples.add(profile, ms_between(t0, t1), call_start_us + profile.team_start_ms * 1e3);
      if (run.after_step) run.after_step();
      if (i % error_every == 0 || i + 1 == steps) {
        worst_error_run = std::max(worst_error_run, scenes::joint_errors(world, run.joints).max);
        if (run.limit_violation_deg)
          worst_limit_run = std::max(worst_limit_run, run.limit_violation_deg());
      }
      bar.update(i + 1);
    }
  }
  world.stop_recording();
  const scenes::JointErrors errors = scenes::joint_errors(world, run.joints);
  const SolverLayout layout = world.solver_layout();
  const double ms = median(samples.step_ms);
  // Each sub-step solves every row `iterations` times and relaxes it `relax` times, unless
  // the plan runs no relax pass (springs only: springs are not relaxed).
  const bool relaxed = world.step_plan().runs(PlanStage::Relax);
  const double joint_row_solves =
      run.rows * settings.substeps *
      (settings.solve_iterations + (relaxed ? settings.relax_iterations : 0));
  // Contacts are relaxed whenever there are relax passes (rigid, unbiased normal rows); their
  // solve passes leave the friction rows out when contact_friction_while_solving says so.
  const double contact_rows_per_pass = contact_samples.median_rows();
  const double contact_solve_rows =
      contact_rows_per_pass -
      (contact_friction_while_solving(settings) ? 0.0 : contact_samples.median_friction_rows());
  const double contact_row_solves =
      settings.substeps * (contact_solve_rows * settings.solve_iterations +
                           contact_rows_per_pass * settings.relax_iterations);
  const double row_solves = joint_row_solves + contact_row_solves;
  const StageTimes stage_median = stage_medians(samples.stage_ms);
  const double stretch = run.stretch_ratio ? run.stretch_ratio() : kNaN;
  const double limit_now = run.limit_violation_deg ? run.limit_violation_deg() : kNaN;

  std::printf("scene            %s\n", run.description.c_str());
  std::printf("bodies / joints  %zu / %zu (%.0f joint rows)\n", world.body_count(),
              world.joint_count(), run.rows);
  std::printf(
      "settings         %ld steps of 1/60 s, %d sub-steps, %d solve + %d relax iterations, simd "
      "%s (%d lanes)%s%s\n",
      steps, settings.substeps, settings.solve_iterations, settings.relax_iterations,
      simd_width_name(layout.simd), layout.lanes, settings.warm_start ? "" : ", no warm start",
      contact_friction_while_solving(settings) ? "" : ", contact friction while relaxing only");
  const std::string policy =
      settings.fixed_threads ? "fixed by --threads-fixed"
                             : "the adaptive policy switched " +
                                   std::to_string(world.last_step_profile().thread_switches) +
                                   " times";
  std::printf("threads          %ld of %ld steps on more than one thread (last step: %d), %s\n",
              samples.shared_steps, steps, world.last_step_profile().threads, policy.c_str());
  std::string per_color;
  for (std::uint32_t n : layout.joints_per_color)
    per_color += (per_color.empty() ? "" : " ") + std::to_string(n);
  if (layout.colors_used == 0 && layout.overflow_joints == 0) {
    // A contact-only scene: the joints' colouring has nothing to say (no lanes to fill); the
    // contacts' own colours are on the contacts line.
    std::printf("colors           no joints in lanes (contact colours: on the contacts line)\n");
  } else {
    std::printf("colors           %d used (joints per color: %s), overflow %u, lane fill %.3f\n",
                layout.colors_used, per_color.c_str(), layout.overflow_joints, layout.lane_fill);
  }
  std::printf("awake bodies     %zu, sleeping islands %zu\n", world.step_plan().awake_bodies,
              world.step_plan().sleeping_islands);
  print_contacts_line(contact_samples, world.step_plan(), world.settings());
  if (show_plan) {
    std::printf("\n");
    print_plan(world.step_plan());
  }
  print_stage_table(stage_median, ms);
  print_contact_stage_lines(contact_samples, ms);
  std::printf("  %-22s %8.3f  (wall time around World::step, median of %ld steps)\n",
              "step() call", ms, steps);
  std::printf("\n");
  if (contact_row_solves > 0.0) {
    std::printf("row solves / s   %.3g (ns per row solve %.2f; per step %.0f joint + %.0f contact "
                "row solves)\n",
                row_solves / (ms * 1e-3), ms * 1e6 / row_solves, joint_row_solves,
                contact_row_solves);
  } else {
    std::printf("row solves / s   %.3g (ns per row solve %.2f)\n", row_solves / (ms * 1e-3),
                ms * 1e6 / row_solves);
  }
  std::printf("barrier wait     %.1f %% of thread time\n", 100.0 * median(samples.wait_share));
  print_serial_share(samples);
  std::printf(
      "joint error      max %.6g m, rms %.6g m after the last step; worst over the run %.6g m\n",
      errors.max, errors.rms, worst_error_run);
  if (run.stretch_ratio) {
    std::printf(
        "stretch ratio    %.6g (path length through the bodies / rest length, worst chain or "
        "column)\n",
        stretch);
  }
  if (run.limit_violation_deg) {
    std::printf(
        "limit violation  %.4g deg after the last step; worst over the run %.4g deg (cone, "
        "twist or hinge limit)\n",
        limit_now, worst_limit_run);
  }
  if (run.reading) std::printf("%s", run.reading().c_str());
  if (twin) twin->finish(world, samples.step_ms);
  const StepTraffic traffic = step_traffic(world);
  print_traffic(traffic, stage_median, ms, o.bandwidth_gbps);
  std::printf("state hash       %016llx\n", static_cast<unsigned long long>(world.state_hash()));

  if (!json_path.empty()) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx",
                  static_cast<unsigned long long>(world.state_hash()));
    const nlohmann::json j = {
        {"scene", choice.scene},
        {"description", run.description},
        {"bodies", world.body_count()},
        {"joints", world.joint_count()},
        {"steps", steps},
        {"substeps", settings.substeps},
        {"solve_iterations", settings.solve_iterations},
        {"relax_iterations", settings.relax_iterations},
        {"contact_friction_while_solving", contact_friction_while_solving(settings)},
        {"threads", world.last_step_profile().threads},
        {"shared_steps", samples.shared_steps},
        {"thread_switches", world.last_step_profile().thread_switches},
        {"simd", simd_width_name(layout.simd)},
        {"ms_per_step", ms},
        {"stage_ms", stage_json(stage_median)},
        {"rows_per_second", row_solves / (ms * 1e-3)},
        {"joint_rows", run.rows},
        {"contact_rows", run.contacts ? contact_rows_per_pass : kNaN},
        {"ns_per_row_solve", ms * 1e6 / row_solves},
        {"barrier_wait_share", median(samples.wait_share)},
        {"serial_share", median(samples.serial_share)},
        {"colors", layout.colors_used},
        {"overflow_joints", layout.overflow_joints},
        {"max_joint_error_m", errors.max},
        {"rms_joint_error_m", errors.rms},
        {"max_joint_error_run_m", worst_error_run},
        {"stretch_ratio", stretch},
        {"limit_violation_deg", limit_now},
        {"limit_violation_run_deg", run.limit_violation_deg ? worst_limit_run : kNaN},
        {"scene_contacts_ms", run.contacts ? median(contact_samples.collision_ms) : kNaN},
        {"contacts", contacts_json(contact_samples, world.step_plan(), world.settings())},
        {"plan", plan_json(world.step_plan())},
        {"awake_bodies", world.step_plan().awake_bodies},
        {"sleeping_islands", world.step_plan().sleeping_islands},
        {"memory", traffic_json(traffic, stage_median, ms, o.bandwidth_gbps)},
        {"state_hash", hash}};
    write_file(json_path, j.dump(2) + "\n");
  }
  if (!csv_path.empty()) {
    std::vector<CsvColumn> contact_columns;
    if (run.contacts) {
      contact_columns = {{"contact_load_ms", &contact_load_ms},
                         {"collision_ms", &contact_samples.collision_ms}};
    }
    write_file(csv_path, steps_csv(samples.step_ms, samples.stage_ms, samples.threads,
                                   contact_columns));
  }
  if (!trace_path.empty()) write_file(trace_path, samples.trace.text());
  return 0;
}

}  // namespace softstep::tool
