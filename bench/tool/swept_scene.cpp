#include "tool/swept_scene.hpp"

#include <chrono>
#include <fstream>
#include <span>
#include <sstream>

#include "softstep/recording.hpp"
#include "tool/elapsed_ms.hpp"

namespace softstep::tool {

namespace {

constexpr double kSceneDt = 1.0 / 60.0;

}  // namespace

SweptScene::SweptScene(const SceneChoice& choice, long scene_steps) : choice_(choice) {
  if (!is_recording()) {
    steps_ = scene_steps;
    uniform_dt_ = kSceneDt;
    return;
  }
  std::ifstream in(choice.scene, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  recording_ = bytes.str();
  double first_dt = 0.0;
  bool uniform = true;
  ReplayHooks hooks;
  hooks.check = false;
  hooks.adjust_settings = [](WorldSettings& s) {
    s.substeps = 1;
    s.solve_iterations = 1;
    s.relax_iterations = 0;
  };
  hooks.before_step = [&](World&, long step, double dt) {
    if (step == 1) first_dt = dt;
    uniform = uniform && dt == first_dt;
    steps_ = step;
  };
  replay_recording_bytes(recording_, choice.scene, hooks);
  uniform_dt_ = uniform ? first_dt : 0.0;
}

std::string SweptScene::steps_text() const {
  if (is_recording()) return std::to_string(steps_) + " recorded steps";
  return std::to_string(steps_) + " steps of 1/60 s";
}

void SweptScene::run(const std::function<void(WorldSettings&)>& knobs,
                     const SweepRunHooks& hooks) const {
  if (is_recording()) return replay(knobs, hooks);
  WorldSettings settings = scene_settings(choice_);
  knobs(settings);
  World world(settings);
  SceneRun run = build_scene(world, choice_);
  if (hooks.start) hooks.start(world, run);
  for (long i = 1; i <= steps_; ++i) {
    if (hooks.before_step) hooks.before_step(world, i);
    const std::span<const ContactManifold> contacts =
        run.contacts ? run.contacts() : std::span<const ContactManifold>();
    const auto t0 = std::chrono::steady_clock::now();
    if (run.contacts) world.step(kSceneDt, contacts);
    else world.step(kSceneDt);
    const double ms = elapsed_ms(t0);
    if (run.after_step) run.after_step();
    if (hooks.after_step) hooks.after_step(world, run, i, ms);
  }
  if (hooks.finish) hooks.finish(world, run);
}

void SweptScene::replay(const std::function<void(WorldSettings&)>& knobs,
                        const SweepRunHooks& hooks) const {
  SceneRun run;
  std::chrono::steady_clock::time_point t0;
  ReplayHooks replay;
  replay.check = false;
  replay.adjust_settings = knobs;
  replay.on_start = [&](World& world) {
    run = describe_world(world, "recording " + choice_.scene);
    if (hooks.start) hooks.start(world, run);
  };
  replay.before_step = [&](World& world, long step, double) {
    if (hooks.before_step) hooks.before_step(world, step);
    t0 = std::chrono::steady_clock::now();
  };
  replay.after_step = [&](World& world, long step, double) {
    const double ms = elapsed_ms(t0);
    run.bodies = dynamic_bodies(world);
    run.joints = world.joint_ids();
    if (hooks.after_step) hooks.after_step(world, run, step, ms);
    if (step == steps_ && hooks.finish) hooks.finish(world, run);
  };
  replay_recording_bytes(recording_, choice_.scene, replay);
}

}  // namespace softstep::tool
