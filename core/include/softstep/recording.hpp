// Recordings: World::start_recording(path) writes the world as it is, then every call that
// changes it and every step with its dt and the motion hash after it, in a compact binary file
// with a versioned header. replay_recording re-runs it and checks the motion hash after every
// step (README, "Recordings", has the format).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "softstep/world.hpp"

namespace softstep {

// A recording that cannot be read (truncated, corrupted, of another version), or whose replay
// does not reproduce it. The message names the file, and the step or byte where it went wrong.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReplayReport {
  long steps = 0;                // steps replayed, each matching its recorded motion hash
  long calls = 0;                // other calls replayed
  std::uint64_t state_hash = 0;  // World::state_hash() at the end, equal to the recorded one
  long contact_steps = 0;        // of the steps, those given contacts (step(dt, contacts))
  long contact_manifolds = 0;    // manifolds given to those steps, all steps together
};

// What a caller may do around a replay. A checked replay (the default) must reproduce the
// recording: anything here that changes what a step computes makes it fail at that step.
struct ReplayHooks {
  // Once, on the world loaded from the initial scene (after adjust_settings), before any
  // record is replayed: to turn on profiling, for instance.
  std::function<void(World& world)> on_start;
  // Around each step (numbered from 1), with its dt: before_step just before World::step,
  // after_step right after it (a checked replay has compared the motion hash by then).
  std::function<void(World& world, long step, double dt)> before_step;
  std::function<void(World& world, long step, double dt)> after_step;
  // Applied to the settings the world starts with and to those of every set_settings record,
  // so that they hold for the whole replay: the threads or SIMD width of a checked replay
  // (which never change a result), the sub-steps or iterations of an unchecked one.
  std::function<void(WorldSettings& settings)> adjust_settings;
  // false: an unchecked replay, which runs the recorded calls (steps with their dt and
  // contacts, creations, destructions, setters) without comparing the motion hash after each
  // step or the state hash at the end: for replaying a recording at other settings, as
  // softstep sweep FILE does. The file is read as strictly (its initial scene must load into
  // the recorded world, a call must give the recorded id, a refused call is an error).
  bool check = true;
};
ReplayReport replay_recording(const std::string& path, const ReplayHooks& hooks);
ReplayReport replay_recording_bytes(const std::string& bytes, const std::string& name,
                                    const ReplayHooks& hooks);

// Re-runs the recording at `path`. `after_step` (optional) sees the world after each step,
// for profiling or viewing a replay. Throws RecordingError.
ReplayReport replay_recording(
    const std::string& path,
    const std::function<void(World& world, long step, double dt)>& after_step = {});
// The same from the file's bytes; `name` stands for the file in messages.
ReplayReport replay_recording_bytes(
    const std::string& bytes, const std::string& name,
    const std::function<void(World& world, long step, double dt)>& after_step = {});

}  // namespace softstep
