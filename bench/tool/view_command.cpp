#include "tool/view_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "tool/progress_bar.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

void add_view_limits(CLI::App& cmd, ViewLimits& limits) {
  cmd.add_option(
         "--max-bodies", limits.max_bodies,
         "bodies drawn for their own sake (every k-th; the drawn joints' bodies come on top)")
      ->check(whole_in(1, 10000000))
      ->capture_default_str();
  cmd.add_option("--max-joints", limits.max_joints, "joints drawn (every k-th)")
      ->check(whole_in(0, 10000000))
      ->capture_default_str();
  cmd.add_option("--frames", limits.max_frames, "frames kept (evenly spaced over the run)")
      ->check(whole_in(2, 100000))
      ->capture_default_str();
}

CLI::App* add_view_command(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "view", "run a scene and write a page that plays it in 3D, with its per-stage step time");
  add_scene_options(*cmd, o.scene);
  cmd->add_option("--out", o.out, "the folder index.html goes to")->required()->type_name("DIR");
  cmd->add_option("--steps", o.steps, "steps of 1/60 s")
      ->check(whole_in(1, 10000000))
      ->capture_default_str();
  add_view_limits(*cmd, o.limits);
  cmd->footer(
      std::string(
          "The page needs no network: open DIR/index.html in a browser. Large scenes are "
          "subsampled\n(--max-bodies, --max-joints, --frames) so that it stays fluent.\n\n") +
      kSceneHelp);
  return cmd;
}

int view_command(const ViewOptions& o) {
  World world(scene_settings(o.scene));
  const SceneRun run = build_scene(world, o.scene);
  world.set_profiling(true);
  ViewRecorder recorder(world, run.description, o.limits);
  const double dt = 1.0 / 60.0;
  {
    ProgressBar bar("view", o.steps);
    for (long i = 1; i <= o.steps; ++i) {
      step_scene(world, run, dt);
      if (run.after_step) run.after_step();
      recorder.after_step(world, dt);
      bar.update(i);
    }
  }
  std::filesystem::create_directories(o.out);
  const std::string path = o.out + "/index.html";
  const std::string page = recorder.page(&world);
  write_file(path, page);
  std::printf("%s: %zu of %zu bodies, %zu of %zu joints, %zu frames of %ld steps, %.1f MB\n",
              path.c_str(), recorder.drawn_bodies(), world.body_count(), recorder.drawn_joints(),
              world.joint_count(), recorder.frames(), o.steps,
              static_cast<double>(page.size()) / 1e6);
  return 0;
}

}  // namespace softstep::tool
