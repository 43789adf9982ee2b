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

// What a caller may do around a replay without changing it.
struct ReplayHooks {
  // Once, on the world loaded from the initial scene, before any record is replayed: to turn
  // on profiling, or to pick the threads or SIMD width (settings that never change a result).
  // Anything that changes what a step computes makes the replay fail at that step.
  std::function<void(World& world)> on_start;
  std::function<void(World& world, long step, double dt)> after_step;
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
