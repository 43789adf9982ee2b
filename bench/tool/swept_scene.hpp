// What softstep sweep runs once per setting: a scene (built in, or a scene file) built and
// stepped at 1/60 s with its own contacts and bookkeeping (SceneRun), or a recording's calls (steps with their dt and contacts, creations,
// destructions, setters) replayed unchecked, since the swept settings change what its steps
// compute. Either way the sweep sees the same hooks around each step.
#pragma once

#include <functional>
#include <string>

#include "tool/scene_options.hpp"

namespace softstep::tool {

struct SweepRunHooks {
  // Once, on the built or loaded world at the run's settings, before its first step.
  std::function<void(World& world, SceneRun& run)> start;
  // Around each step (numbered from 1); step_ms is the World::step call alone (not the
  // scene's own collision detection or bookkeeping, SceneRun::contacts and after_step).
  std::function<void(World& world, long step)> before_step;
  std::function<void(World& world, SceneRun& run, long step, double step_ms)> after_step;
  // Once, after the last step's after_step (the scene's own readings).
  std::function<void(World& world, SceneRun& run)> finish;
};

class SweptScene {
 public:
  // A recording is read once here and replayed once at its own settings' cheapest solve to
  // count its steps (a bad file fails here, before the sweep starts).
  SweptScene(const SceneChoice& choice, long scene_steps);

  bool is_recording() const { return choice_.from_recording; }
  // Steps per run: the --steps of a scene, a recording's own.
  long steps() const { return steps_; }
  // The dt every step takes, or 0 when a recording's steps differ.
  double uniform_dt() const { return uniform_dt_; }
  // "60 steps of 1/60 s", "240 recorded steps".
  std::string steps_text() const;

  // One run, with `knobs` applied to the scene's settings (a recording's initial ones and
  // those of its set_settings calls). For a recording, run.bodies and run.joints follow its
  // creations and destructions: after each step they are the world's dynamic bodies and
  // joints.
  void run(const std::function<void(WorldSettings&)>& knobs, const SweepRunHooks& hooks) const;

 private:
  void replay(const std::function<void(WorldSettings&)>& knobs, const SweepRunHooks& hooks) const;

  const SceneChoice& choice_;
  long steps_ = 0;
  double uniform_dt_ = 0.0;
  std::string recording_;  // the file's bytes
};

}  // namespace softstep::tool
