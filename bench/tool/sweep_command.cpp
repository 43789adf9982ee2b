// softstep sweep: runs a scene (or replays a recording's calls, swept_scene.hpp) once per
// setting of a grid of knobs, times it and measures its error against the exact references,
// then writes results.csv, pareto.svg and summary.md.
#include "tool/sweep_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "softstep/metrics.hpp"
#include "softstep/reference.hpp"
#include "tool/pareto.hpp"
#include "tool/pareto_chart.hpp"
#include "tool/progress_bar.hpp"
#include "tool/report_files.hpp"
#include "tool/scene_options.hpp"
#include "tool/swept_scene.hpp"

namespace softstep::tool {

namespace {

const char* const kSweepHelp =
    "Every combination of the lists (comma-separated) runs S steps of 1/60 s once to measure\n"
    "its errors and R more times, all settings in turn, to time it: ms per step is the median\n"
    "over the R runs of each run's median step. The errors:\n"
    "  joint error     C of every joint after every step (max, and RMS over steps and joints)\n"
    "  drift           RMS distance of the bodies from the fine-step reference (the same scene\n"
    "                  at --reference-substeps sub-steps and --reference-iterations solve and\n"
    "                  relax iterations), the largest over ~20 samples of the run\n"
    "  reference       at --probes steps: distance of the first sub-step's velocities from the\n"
    "                  exact solution of its soft system (Eigen sparse LDLT), relative, and the\n"
    "                  RMS row residual J v + bias + Gamma P of the solver's result, m/s\n"
    "  energy drift    largest |E - E0| / E0, potential energy from the lowest reachable point\n"
    "--error picks the error of the chart and of the Pareto front.\n"
    "DIR gets results.csv (one row per setting), pareto.svg and summary.md.\n"
    "A recording (World::start_recording, profile ... --record FILE) is swept by replaying its\n"
    "calls at each setting, unchecked (the settings change what its steps compute): its steps\n"
    "with their dt and contacts, and every creation, destruction and setter between them; the\n"
    "swept knobs hold through its own set_settings calls. The reference replays it too.\n\n";

}  // namespace

namespace {

struct Setting {
  int substeps, relax, iterations;
  bool warm_start;
  SimdWidth simd;
  int threads;
  int rigid_hertz;
  SolverMode solver = SolverMode::Iterative;
};

std::string label(const Setting& s) {
  std::string l = std::to_string(s.substeps) + " sub, " + std::to_string(s.relax) + " relax, " +
                  std::to_string(s.iterations) + " it";
  if (!s.warm_start) l += ", cold";
  if (s.rigid_hertz != 60) l += ", " + std::to_string(s.rigid_hertz) + " Hz";
  if (s.solver != SolverMode::Iterative) l += std::string(", ") + solver_mode_name(s.solver);
  return l;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Measured {
  double ms = 0.0;
  double max_joint_error = 0.0;
  double rms_joint_error = 0.0;
  double velocity_residual = 0.0;
  double energy_drift = 0.0;
  double reference_distance = 0.0;
  double drift = 0.0;
  double stretch = 0.0;
  double limit_violation_deg = kNaN;  // worst over the sampled steps (ragdoll)
  SceneReadings scene;                // at the end of the run (vehicle, suspension-bridge)
};

// Potential energy measured from the lowest height any body could reach, so that E0 > 0.
double energy_offset(const World& world, const SceneRun& run) {
  double lowest = std::numeric_limits<double>::infinity(), weight = 0.0;
  const double g = world.settings().gravity.norm();
  const Eigen::Vector3d down =
      g > 0.0 ? Eigen::Vector3d(world.settings().gravity / g) : Eigen::Vector3d::Zero();
  for (BodyId b : run.bodies) {
    const BodyState s = world.body(b);
    lowest = std::min(lowest, -down.dot(s.position));
    weight += s.mass * s.gravity_scale * g;
  }
  return -(lowest - run.reach) * weight;
}

// The bodies' energy with the joints' springs, NaN when the energy metric cannot model one of
// the scene's joints (it models ball and distance joints): the talk's scenes (wheel,
// revolute, swing-twist joints) are swept for their own readings and their time, without
// an energy drift.
double scene_energy(const World& world, const SceneRun& run) {
  try {
    return metrics::mechanical_energy(world, run.bodies, run.joints);
  } catch (const std::invalid_argument&) {
    return kNaN;
  }
}

// The setting's knobs on the scene's settings (a scene file's or recording's, or the
// defaults).
void apply_knobs(const Setting& s, WorldSettings& w) {
  w.substeps = s.substeps;
  w.relax_iterations = s.relax;
  w.solve_iterations = s.iterations;
  w.warm_start = s.warm_start;
  w.simd = s.simd;
  w.threads = s.threads;
  w.rigid_hertz = s.rigid_hertz;
  w.solver = s.solver;
}

// The larger of two error readings, NaN when either is: a run that blew up must not pass
// for accurate because std::max drops NaN.
double worst(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? kNaN : std::max(a, b);
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "what accuracy costs in time: a scene over a grid of settings, with its Pareto front");
  add_scene_options(*cmd, o.scene);
  cmd->add_option("--out", o.out, "the folder the results go to")->required()->type_name("DIR");
  cmd->add_option("--steps", o.steps, "steps of 1/60 s per run (a recording runs its own)")
      ->check(whole_in(2, 1000000))
      ->capture_default_str();
  const auto list = [&](const char* name, std::vector<long>& into, long min, long max,
                        const char* what) {
    cmd->add_option(name, into, what)
        ->delimiter(',')
        ->check(whole_in(min, max))
        ->type_name("LIST")
        ->capture_default_str();
  };
  list("--substeps", o.substeps, 1, 1000, "sub-steps per step");
  list("--relax", o.relax, 0, 1000, "relax passes per sub-step");
  list("--iterations", o.iterations, 1, 1000, "solve passes per sub-step");
  cmd->add_option("--warm-start", o.warm_start, "warm starting: on, off or on,off")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}))
      ->type_name("LIST")
      ->capture_default_str();
  cmd->add_option("--simd", o.simd, "SIMD widths: best, scalar, sse, avx2, avx512")
      ->delimiter(',')
      ->check(CLI::IsMember(simd_names()))
      ->type_name("LIST")
      ->capture_default_str();
  list("--threads", o.threads, 0, 256, "threads (0: all cores)");
  list("--rigid-hertz", o.rigid_hertz, 1, 1000000, "the stiffness rigid rows are solved with, Hz");
  cmd->add_option("--solver", o.solver,
                  "WorldSettings::solver: iterative, direct-for-trees, auto (a list)")
      ->delimiter(',')
      ->check(CLI::IsMember(solver_names()))
      ->type_name("LIST")
      ->capture_default_str();
  cmd->add_option("--runs", o.runs, "timed runs per setting")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--error", o.error, "the error of the chart and the front")
      ->check(CLI::IsMember({"drift", "joint", "reference"}))
      ->capture_default_str();
  cmd->add_option("--reference-substeps", o.reference_substeps,
                  "sub-steps of the fine-step reference")
      ->check(whole_in(1, 10000))
      ->capture_default_str();
  cmd->add_option("--reference-iterations", o.reference_iterations,
                  "solve and relax iterations of the fine-step reference")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--probes", o.probes, "steps checked against the exact sub-step solve")
      ->check(whole_in(0, 1000000))
      ->capture_default_str();
  cmd->footer(std::string(kSweepHelp) + kSceneHelp);
  o.command = cmd;
  return cmd;
}

int sweep_command(const SweepOptions& o) {
  const SceneChoice& choice = o.scene;
  if (choice.from_recording && o.command != nullptr && o.command->count("--steps") > 0)
    throw UsageError("--steps cannot be used with a recording (" + choice.scene +
                     "): a sweep runs all its recorded steps");
  const std::string& out = o.out;
  const std::vector<long>& substeps = o.substeps;
  const std::vector<long>& relax = o.relax;
  const std::vector<long>& iterations = o.iterations;
  const std::vector<long>& threads = o.threads;
  const std::vector<long>& rigid_hertz = o.rigid_hertz;
  const long runs = o.runs;
  const std::string& error_name = o.error;
  const int reference_substeps = o.reference_substeps;
  const int reference_iterations = o.reference_iterations;
  if (o.probes > o.steps)
    throw UsageError("--probes " + std::to_string(o.probes) + ": at most --steps (" +
                     std::to_string(o.steps) + ")");
  // Checked before the runs: a long sweep must not end in a write error.
  check_writable_directory("--out", out);
  // A recording is read (and its steps counted) here, so that a bad file stops the sweep
  // before it starts, with the reader's error.
  const SweptScene subject(choice, o.steps);
  const long steps = subject.steps();
  if (steps == 0) throw UsageError(choice.scene + " has no steps to sweep");
  // A recording's own step count bounds the probes it can take.
  const long probes = std::min(o.probes, steps);

  std::vector<bool> warm_choices;
  for (const char* w : {"on", "off"}) {
    if (std::find(o.warm_start.begin(), o.warm_start.end(), w) != o.warm_start.end())
      warm_choices.push_back(std::string(w) == "on");
  }
  std::vector<SimdWidth> simd_choices;
  for (const std::string& name : simd_names()) {
    if (std::find(o.simd.begin(), o.simd.end(), name) != o.simd.end())
      simd_choices.push_back(parse_simd(name));
  }
  const double dt = subject.uniform_dt();
  std::vector<Setting> grid;
  for (long s : substeps)
    for (long r : relax)
      for (long i : iterations)
        for (bool w : warm_choices)
          for (SimdWidth v : simd_choices)
            for (long t : threads)
              for (long k : rigid_hertz) {
                // Rigid rows are solved at min(rigid_hertz, sub-step rate / 4): a value above
                // the cap runs the same solve as the cap, and is measured once (when every
                // step has the same dt, and so the same cap).
                const double cap = dt > 0.0 ? 0.25 * static_cast<double>(s) / dt : kNaN;
                const auto solved_at = [cap](long hz) {
                  return std::isnan(cap) ? double(hz) : std::min(double(hz), cap);
                };
                const auto first_alike =
                    std::find_if(rigid_hertz.begin(), rigid_hertz.end(),
                                 [&](long other) { return solved_at(other) == solved_at(k); });
                if (*first_alike != k) continue;
                for (const std::string& mode : o.solver) {
                  grid.push_back({static_cast<int>(s), static_cast<int>(r), static_cast<int>(i),
                                  w, v, static_cast<int>(t), static_cast<int>(k),
                                  parse_solver(mode)});
                }
              }

  // Steps at which positions are compared with the reference and energy is measured, and
  // the steps whose first sub-step is checked against the exact solve.
  const long sample_every = std::max(1L, steps / 20);
  const auto sampled = [&](long step) { return step % sample_every == 0 || step == steps; };
  const auto probed = [&](long step) {
    for (long k = 1; k <= probes; ++k) {
      if (step == k * steps / probes) return true;
    }
    return false;
  };

  // The fine-step reference trajectory.
  std::vector<std::vector<Eigen::Vector3d>> reference_positions(
      static_cast<std::size_t>(steps + 1));
  {
    ProgressBar bar("reference", steps);
    SweepRunHooks hooks;
    hooks.after_step = [&](World& world, SceneRun& run, long i, double) {
      if (sampled(i))
        reference_positions[static_cast<std::size_t>(i)] = positions(world, run.bodies);
      bar.update(i);
    };
    subject.run(
        [&](WorldSettings& fine) {
          fine.substeps = reference_substeps;
          fine.solve_iterations = reference_iterations;
          fine.relax_iterations = reference_iterations;
        },
        hooks);
  }

  std::string description;
  std::size_t body_count = 0, joint_count = 0;
  std::vector<Measured> results(grid.size());
  {
    // Round 0 measures the errors; rounds 1..runs time the steps. A round runs every setting
    // once, so a burst of load from elsewhere on the machine hits one run of many settings
    // rather than every run of one.
    std::vector<std::vector<double>> run_ms(grid.size());
    const auto settings_count = static_cast<long>(grid.size());
    ProgressBar bar("sweep", settings_count * (runs + 1));
    for (long r = 0; r <= runs; ++r) {
      for (std::size_t g = 0; g < grid.size(); ++g) {
        const Setting& setting = grid[g];
        Measured& m = results[g];
        const bool measuring = r == 0;
        double offset = 0.0, e0 = 0.0, sum_sq = 0.0;
        std::vector<double> step_ms;
        SweepRunHooks hooks;
        hooks.start = [&](World& world, SceneRun& run) {
          description = run.description;
          body_count = world.body_count();
          joint_count = world.joint_count();
          if (!measuring) return;
          offset = energy_offset(world, run);
          e0 = scene_energy(world, run) + offset;
          if (run.limit_violation_deg) m.limit_violation_deg = 0.0;
        };
        // Capturing costs a copy, outside the timed step.
        hooks.before_step = [&](World& world, long i) {
          world.set_solve_capture(measuring && probed(i));
        };
        hooks.after_step = [&](World& world, SceneRun& run, long i, double ms) {
          if (!measuring) {
            step_ms.push_back(ms);
            return;
          }
          const scenes::JointErrors e = scenes::joint_errors(world, run.joints);
          m.max_joint_error = worst(m.max_joint_error, e.max);
          sum_sq += e.rms * e.rms;
          if (sampled(i)) {
            const double energy = scene_energy(world, run) + offset;
            m.energy_drift =
                worst(m.energy_drift, e0 != 0.0 ? std::abs(energy - e0) / std::abs(e0) : kNaN);
            m.drift = worst(
                m.drift, metrics::position_drift(world, run.bodies,
                                                 reference_positions[static_cast<std::size_t>(i)]));
            if (run.stretch_ratio) m.stretch = worst(m.stretch, run.stretch_ratio());
            if (run.limit_violation_deg)
              m.limit_violation_deg = worst(m.limit_violation_deg, run.limit_violation_deg());
          }
          if (probed(i)) {
            try {
              const reference::SoftSystem system = reference::first_substep_system(world);
              const reference::ExactSolution exact = reference::solve_exact(system);
              const Eigen::VectorXd residual = reference::row_residual(
                  system, system.velocity_after_solve, system.impulse_after_solve);
              m.reference_distance =
                  worst(m.reference_distance, reference::reference_distance(system, exact));
              m.velocity_residual = worst(
                  m.velocity_residual,
                  residual.size() ? residual.norm() / std::sqrt(double(residual.size())) : 0.0);
            } catch (const std::exception&) {
              m.reference_distance = m.velocity_residual = kNaN;
            }
          }
        };
        hooks.finish = [&](World&, SceneRun& run) {
          if (measuring && run.readings) m.scene = run.readings();
        };
        subject.run([&](WorldSettings& w) { apply_knobs(setting, w); }, hooks);
        if (measuring) {
          m.rms_joint_error = std::sqrt(sum_sq / static_cast<double>(steps));
          // A run that blew up has no meaningful error.
          if (!std::isfinite(m.max_joint_error) || !std::isfinite(m.drift))
            m.max_joint_error = m.rms_joint_error = m.drift = kNaN;
        }
        if (!measuring) run_ms[g].push_back(median(step_ms));
        bar.update(r * settings_count + static_cast<long>(g) + 1);
      }
    }
    for (std::size_t g = 0; g < grid.size(); ++g) results[g].ms = median(run_ms[g]);
  }

  const auto error_of = [&](const Measured& m) {
    return error_name == "drift"   ? m.drift
           : error_name == "joint" ? m.max_joint_error
                                   : m.reference_distance;
  };
  const char* error_axis =
      error_name == "drift"
          ? "drift from the fine-step reference (m, RMS over bodies, worst sample)"
      : error_name == "joint" ? "max joint error |C| (m, worst step)"
                              : "distance from the exact sub-step solve (relative)";
  std::vector<CostPoint> points;
  std::vector<std::string> labels;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    points.push_back({results[g].ms, error_of(results[g])});
    labels.push_back(label(grid[g]));
  }
  const std::vector<bool> front = pareto_front(points);

  std::filesystem::create_directories(out);
  std::string csv =
      "substeps,relax,iterations,warm_start,simd,threads,rigid_hertz,ms_per_step,max_joint_error_m,"
      "rms_joint_error_m,velocity_residual,energy_drift,reference_distance,drift_m,stretch,"
      "pareto,solver,limit_violation_deg,bounce_hz,bounce_error,ride_height_error_m,sag_error,"
      "crossing_s\n";
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const Setting& s = grid[g];
    const Measured& m = results[g];
    csv += std::to_string(s.substeps) + "," + std::to_string(s.relax) + "," +
           std::to_string(s.iterations) + "," + (s.warm_start ? "1" : "0") + "," +
           simd_width_name(s.simd) + "," + std::to_string(s.threads) + "," +
           std::to_string(s.rigid_hertz) + "," + format_number(m.ms) + "," +
           format_number(m.max_joint_error) + "," + format_number(m.rms_joint_error) + "," +
           format_number(m.velocity_residual) + "," + format_number(m.energy_drift) + "," +
           format_number(m.reference_distance) + "," + format_number(m.drift) + "," +
           format_number(m.stretch) + "," + (front[g] ? "1" : "0") + "," +
           solver_mode_name(s.solver) + "," + format_number(m.limit_violation_deg) + "," +
           format_number(m.scene.bounce_hz) + "," + format_number(m.scene.bounce_error) + "," +
           format_number(m.scene.ride_height_error_m) + "," + format_number(m.scene.sag_error) +
           "," + format_number(m.scene.crossing_s) + "\n";
  }
  write_file(out + "/results.csv", csv);
  const std::string title = description + ": " + subject.steps_text();
  write_file(out + "/pareto.svg",
             pareto_svg(points, front, labels,
                        {title, "time per step (ms, median of " + std::to_string(runs) + " runs)",
                         error_axis}));

  // The front, fastest first, as the budget table.
  std::vector<std::size_t> order;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    if (front[g]) order.push_back(g);
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return points[a].ms < points[b].ms; });
  char line[512];
  std::string md = "# softstep sweep: " + title + "\n\n" + std::to_string(body_count) +
                   " bodies, " + std::to_string(joint_count) + " joints; " +
                   std::to_string(grid.size()) + " settings; error: " + error_axis + ".\n\n" +
                   "| time budget (ms per step) | most accurate setting | ms per step | error | "
                   "max joint error (m) | exact-solve distance | energy drift |\n"
                   "|---|---|---|---|---|---|---|\n";
  for (std::size_t g : order) {
    const Measured& m = results[g];
    std::snprintf(line, sizeof line, "| >= %.3g | %s | %.3g | %.3g | %.3g | %.3g | %.3g |\n", m.ms,
                  labels[g].c_str(), m.ms, points[g].error, m.max_joint_error, m.reference_distance,
                  m.energy_drift);
    md += line;
  }
  md += "\nBelow " +
        (order.empty() ? std::string("any budget")
                       : format_number(points[order.front()].ms) + " ms") +
        " no setting fits. Every setting is in results.csv; pareto.svg draws them.\n";
  write_file(out + "/summary.md", md);
  std::fputs(md.c_str(), stdout);
  return 0;
}

}  // namespace softstep::tool
