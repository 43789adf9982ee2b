// softstep_contacts: steps a contact scene with Bullet's narrow phase and prints where a step's
// time goes, the user's collision detection apart from softstep's solve.
//   softstep_contacts pyramid --base 100 --steps 300 --threads 1 --simd avx2
//   softstep_contacts pile --count 1000
//   softstep_contacts pyramid --base 20 --steps 120 --record pyramid.rec
//     (then: softstep replay pyramid.rec, softstep profile pyramid.rec)
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <optional>
#include <cstdio>
#include <string>
#include <vector>

#include "contacts/contact_scenes.hpp"
#include "softstep/scene_file.hpp"

namespace {

using softstep::SimdWidth;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Contact scenes with Bullet's narrow phase: collision vs solve time"};
  std::string scene = "pyramid";
  int base = 100, count = 1000, steps = 300, threads = 1, substeps = 4;
  std::string simd = "best";
  std::string record_path, overhead_path;
  app.add_option("scene", scene, "pyramid or pile")->check(CLI::IsMember({"pyramid", "pile"}));
  app.add_option("--base", base, "pyramid: boxes in the bottom row")->check(CLI::Range(1, 1000));
  app.add_option("--count", count, "pile: bodies dropped")->check(CLI::Range(1, 100000));
  app.add_option("--steps", steps, "steps of 1/60 s")->check(CLI::Range(1, 1000000));
  app.add_option("--threads", threads, "solver threads (fixed)")->check(CLI::Range(1, 64));
  app.add_option("--substeps", substeps, "sub-steps per step")->check(CLI::Range(1, 64));
  app.add_option("--simd", simd, "scalar, sse, avx2 or best")
      ->check(CLI::IsMember({"scalar", "sse", "avx2", "best"}));
  app.add_option("--record", record_path,
                 "write a recording of the run (World::start_recording): every step's contacts "
                 "included, for softstep replay and softstep profile");
  app.add_option("--recording-overhead", overhead_path,
                 "measure what recording costs: a twin of the world (loaded from its scene) "
                 "records to this file while the world does not; both take the same contacts "
                 "each step, stepped alternately, and the step() calls' medians are compared")
      ->excludes("--record");
  CLI11_PARSE(app, argc, argv);

  softstep::WorldSettings s;
  s.threads = threads;
  s.fixed_threads = true;
  s.substeps = substeps;
  s.sleeping = false;  // measure the solve of every body, every step
  s.simd = simd == "scalar" ? SimdWidth::Scalar
           : simd == "sse"  ? SimdWidth::Sse
           : simd == "avx2" ? SimdWidth::Avx2
                            : SimdWidth::Best;
  softstep::bench::ContactScene sc = scene == "pyramid" ? softstep::bench::make_pyramid(base, s)
                                                        : softstep::bench::make_pile(count, s);
  softstep::World& world = *sc.world;
  world.set_profiling(true);
  std::vector<Eigen::Vector3d> start;
  for (softstep::BodyId id : sc.dynamic) start.push_back(world.body(id).position);

  if (!record_path.empty()) world.start_recording(record_path);
  // The twin stays bit-identical to the world (same start, same contacts: the design's
  // determinism), so the contacts found for the world are the twin's too.
  std::optional<softstep::World> twin;
  std::vector<double> twin_wall_ms;
  if (!overhead_path.empty()) {
    twin.emplace(softstep::load_scene_text(softstep::save_scene_text(world), "twin"));
    twin->set_profiling(true);
    twin->start_recording(overhead_path);
  }

  std::vector<double> collision_ms, step_ms, wall_ms, load_ms, serial_ms;
  std::vector<std::array<double, softstep::kStageCount>> stage_ms;
  std::size_t manifolds = 0, points = 0;
  for (int i = 0; i < steps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto& contacts = sc.collision->find(world, sc.friction, sc.restitution);
    const auto t1 = std::chrono::steady_clock::now();
    const auto timed_step = [&](softstep::World& w) {
      const auto a = std::chrono::steady_clock::now();
      w.step(1.0 / 60.0, contacts);
      return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a)
          .count();
    };
    // Alternating which goes first, so neither always finds the other's data in the cache.
    if (twin && i % 2 == 1) twin_wall_ms.push_back(timed_step(*twin));
    wall_ms.push_back(timed_step(world));
    if (twin && i % 2 == 0) twin_wall_ms.push_back(timed_step(*twin));
    collision_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    const softstep::StepProfile& p = world.last_step_profile();
    step_ms.push_back(p.step_ms);
    load_ms.push_back(p.contact_load_ms);
    serial_ms.push_back(p.serial_ms);
    stage_ms.push_back(p.stage_ms);
    manifolds = contacts.size();
    points = 0;
    for (const auto& m : contacts) points += static_cast<std::size_t>(m.point_count);
  }
  if (!record_path.empty()) world.stop_recording();
  if (twin) {
    twin->stop_recording();
    if (twin->state_hash() != world.state_hash()) {
      std::fprintf(stderr, "the recording twin diverged from the world\n");
      return 1;
    }
  }
  double moved = 0.0;
  for (std::size_t i = 0; i < sc.dynamic.size(); ++i) {
    moved = std::max(moved, (world.body(sc.dynamic[i]).position - start[i]).norm());
  }
  const softstep::StepPlan& plan = world.step_plan();
  std::printf("scene            %s: %zu dynamic bodies, %d steps of 1/60 s, %d sub-steps\n",
              scene.c_str(), sc.dynamic.size(), steps, substeps);
  std::printf("solver           %s, %d thread(s)\n", softstep::simd_width_name(world.solver_layout().simd),
              threads);
  std::printf("contacts (last)  %zu manifolds, %zu points, %zu colours, %zu in overflow\n",
              manifolds, points, plan.contact_colors, plan.contact_overflow);
  std::printf("largest move     %.4f m (from the start pose, over the run)\n", moved);
  std::printf("median ms/step   collision (Bullet, the user's) %.3f | softstep step %.3f\n",
              median(collision_ms), median(step_ms));
  std::printf("  softstep parts contact load (match, colour, pack) %.3f\n", median(load_ms));
  std::printf("  serial         %.3f (of the call, on one thread: checks, contact load and store, "
              "plan, sleep)\n",
              median(serial_ms));
  // The call as the caller sees it: the step plus, with --record, writing its contacts.
  std::printf("  step() call    %.3f (wall, around world.step%s)\n", median(wall_ms),
              record_path.empty() ? "" : ", recording included");
  if (twin) {
    std::vector<double> ratio;
    for (std::size_t k = 0; k < wall_ms.size(); ++k) ratio.push_back(twin_wall_ms[k] / wall_ms[k]);
    std::printf("  recording      %.3f ms/step recording vs %.3f plain (step() calls, alternated); "
                "median per-step ratio %.3f\n",
                median(twin_wall_ms), median(wall_ms), median(ratio));
  }
  for (int st = 0; st < softstep::kStageCount; ++st) {
    std::vector<double> v;
    for (const auto& a : stage_ms) v.push_back(a[static_cast<std::size_t>(st)]);
    std::printf("  %-22s %.3f\n", softstep::stage_name(static_cast<softstep::Stage>(st)), median(v));
  }
  const double rows = double(points) * 3.0;  // normal + 2 friction rows per point
  const std::size_t passes = std::size_t(substeps) * 2;  // solve + relax
  std::vector<double> solve_relax;
  for (const auto& a : stage_ms) {
    solve_relax.push_back(a[static_cast<std::size_t>(softstep::Stage::Solve)] +
                          a[static_cast<std::size_t>(softstep::Stage::Relax)]);
  }
  std::printf("contact rows     %.0f per pass: %.2f ns per row (solve + relax stages, incl. barriers)\n",
              rows, median(solve_relax) * 1e6 / (rows * double(passes)));
  return 0;
}
