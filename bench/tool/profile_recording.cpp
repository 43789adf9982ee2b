#include "tool/profile_recording.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "softstep/recording.hpp"
#include "tool/arguments.hpp"
#include "tool/contact_report.hpp"
#include "tool/plan_report.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

namespace {

// The options that change what a step computes: a recording replays with its own, or its
// steps would no longer match. (--threads, --threads-fixed, --simd and --general never change
// a result, so they apply from the first record.)
void refuse_result_changing_options(const ProfileOptions& o) {
  for (const char* option :
       {"--steps", "--substeps", "--iterations", "--relax", "--no-warm-start", "--no-sleep",
        "--no-friction-while-solving", "--save", "--record", "--recording-overhead"}) {
    if (o.command != nullptr && o.command->count(option) > 0) {
      throw UsageError(std::string(option) + " cannot be used with a recording (" +
                       o.scene.scene +
                       "): it replays its own steps and settings, and every step must match");
    }
  }
}

}  // namespace

int profile_recording(const ProfileOptions& o) {
  refuse_result_changing_options(o);
  check_writable_file("--json", o.json_path);
  check_writable_file("--csv", o.csv_path);
  check_writable_file("--trace", o.trace_path);
  const auto given = [&](const char* option) {
    return o.command != nullptr && o.command->count(option) > 0;
  };

  StepSamples samples;
  samples.tracing = !o.trace_path.empty();
  double clock_us = 0.0;  // the steps laid end to end on the trace's clock
  // The world as it ends, for the figures that need one.
  StepPlan plan;
  WorldSettings settings;
  SolverLayout layout{};
  std::size_t bodies = 0, joints = 0;
  int threads = 1;
  // Of the steps with contacts: manifolds, points and softstep's share of taking them (the
  // contacts themselves are not seen here: no rows figure).
  ContactSamples contacts;
  ReplayHooks hooks;
  // Kept through the recording's own set_settings calls.
  hooks.adjust_settings = [&](WorldSettings& s) {
    if (given("--threads")) s.threads = o.settings.threads;
    if (o.threads_fixed) s.fixed_threads = true;
    if (given("--simd")) s.simd = parse_simd(o.simd);
    if (o.general) s.specialize = false;
  };
  hooks.on_start = [&](World& world) { world.set_profiling(true); };
  hooks.after_step = [&](World& world, long, double) {
    const StepProfile& p = world.last_step_profile();
    samples.add(p, p.step_ms, clock_us);
    clock_us += p.step_ms * 1e3;
    plan = world.step_plan();
    settings = world.settings();
    layout = world.solver_layout();
    bodies = world.body_count();
    joints = world.joint_count();
    threads = p.threads;
    // A recording holds no manifolds to count rows from: unknown, as profile_command's NaN.
    constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    contacts.add_step(world, {kUnknown, kUnknown});
  };
  ReplayReport report;
  try {
    report = replay_recording(o.scene.scene, hooks);
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "softstep profile: %s\n", e.what());
    return 1;
  }
  if (report.steps == 0) {
    std::fprintf(stderr, "softstep profile: %s has no steps to profile\n", o.scene.scene.c_str());
    return 1;
  }

  const double ms = median(samples.step_ms);
  const StageTimes stage_median = stage_medians(samples.stage_ms);
  std::printf("recording        %s: %ld steps and %ld other calls replayed, every step matched\n",
              o.scene.scene.c_str(), report.steps, report.calls);
  std::printf("bodies / joints  %zu / %zu at the end (%llu rows per pass)\n", bodies, joints,
              static_cast<unsigned long long>(plan.rows_per_pass));
  std::printf("last step        %d thread(s), simd %s (%d lanes), %d colors\n", threads,
              simd_width_name(layout.simd), layout.lanes, layout.colors_used);
  if (o.show_plan) {
    std::printf("\n");
    print_plan(plan);
  }
  print_contacts_line(contacts, plan, settings);
  print_stage_table(stage_median, ms);
  print_contact_stage_lines(contacts, ms);
  std::printf("  %-22s %8.3f  (median of %ld steps; the slowest %.3f)\n\n", "step", ms,
              report.steps, *std::max_element(samples.step_ms.begin(), samples.step_ms.end()));
  std::printf("barrier wait     %.1f %% of thread time\n", 100.0 * median(samples.wait_share));
  print_serial_share(samples);
  std::printf("state hash       %016llx\n", static_cast<unsigned long long>(report.state_hash));

  if (!o.json_path.empty()) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx",
                  static_cast<unsigned long long>(report.state_hash));
    nlohmann::json j = {{"recording", o.scene.scene},
                              {"steps", report.steps},
                              {"calls", report.calls},
                              {"bodies", bodies},
                              {"joints", joints},
                              {"threads", threads},
                              {"simd", simd_width_name(layout.simd)},
                              {"ms_per_step", ms},
                              {"stage_ms", stage_json(stage_median)},
                              {"barrier_wait_share", median(samples.wait_share)},
                              {"serial_share", median(samples.serial_share)},
                              {"contacts", contacts_json(contacts, plan, settings)},
                              {"plan", plan_json(plan)},
                              {"state_hash", hash}};
    j["contacts"]["manifolds"] = report.contact_manifolds;  // given, over every step
    write_file(o.json_path, j.dump(2) + "\n");
  }
  if (!o.csv_path.empty()) write_file(o.csv_path, steps_csv(samples.step_ms, samples.stage_ms, samples.threads));
  if (!o.trace_path.empty()) write_file(o.trace_path, samples.trace.text());
  return 0;
}

}  // namespace softstep::tool
