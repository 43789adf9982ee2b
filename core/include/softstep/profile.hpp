// Where the time of a step went, per stage and per thread. Recorded only while profiling is
// on (World::set_profiling); off, a stage costs one branch more.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace softstep {

enum class Stage : std::uint8_t {
  Prepare,              // body records, anchors, softness; the contacts' lanes (once per step)
  IntegrateVelocities,  // gravity and damping (per sub-step)
  WarmStart,            // apply the previous sub-step's impulses, or clear them (per sub-step)
  Solve,                // soft, biased pass (per sub-step)
  IntegratePositions,   // (per sub-step)
  Relax,                // rigid, unbiased passes (per sub-step)
  Store,                // poses, velocities, contact readings back to the world (once per step)
  Restitution,          // the contacts' bounce pass after the sub-steps (only when asked)
};
// Restitution is last: the count follows the enum.
inline constexpr int kStageCount = static_cast<int>(Stage::Restitution) + 1;
const char* stage_name(Stage stage);  // "prepare", "integrate_velocities", ...

// One stage run by one thread: [start, end) in microseconds since the step began.
struct StageEvent {
  Stage stage;
  double start_us;
  double end_us;
};

struct StepProfile {
  // The threads' team (the stages) and the contact load when it ran alone before them.
  double step_ms = 0.0;
  std::array<double, kStageCount>
      stage_ms{};  // wall time per stage on thread 0, summed over sub-steps
  std::vector<std::vector<StageEvent>> thread_events;  // per thread, in order
  std::vector<double> barrier_wait_ms;                 // per thread: time spent waiting at barriers
  int threads = 1;  // threads this step ran on (the adaptive policy's choice, or the setting)
  // How often the adaptive policy changed the thread count since the world was made (its
  // trials of the other count included): a count that keeps rising means two threads and
  // one run about equally fast, or another process takes a core from time to time.
  long thread_switches = 0;
  // Checking every field of the step's contacts and indexing their keys, before anything
  // changes: on check_threads threads (the step's, when it has 4,096 manifolds or more), then
  // the keys' index on one.
  double contact_check_ms = 0.0;
  int check_threads = 1;
  // Taking the step's contacts in: colouring them and ordering them by colour, on one thread
  // (the caller's collision detection is outside the step). With the checks on more than one
  // thread, the second lays them out beside the checks (contact_load_beside_checks: then this
  // is within contact_check_ms); otherwise, or when a contact woke an island, after them.
  // Matching them with the last step's cache and packing their lanes run on the step's
  // threads in the prepare stage; reading their impulses back, in the store stage.
  double contact_load_ms = 0.0;
  bool contact_load_beside_checks = false;
  // The load kept the last step's layout: every manifold asked for what it asked for then
  // (bodies, point count; friction, rolling resistance and restitution on or off) and no body
  // was created, destroyed, put to sleep or woken since. The checks compared them as they read
  // them; the load then only placed them in the next warm-start cache.
  bool contact_layout_kept = false;
  // The whole step() call, wall time, and when in it the checks and the team started.
  double call_ms = 0.0;
  double check_start_ms = 0.0, team_start_ms = 0.0;
  // Of call_ms, the time one thread runs whatever the thread count, outside the threads'
  // team and the shared contact checks: checking the input (the contacts' too when on one
  // thread), the plan, the contact load when alone, the geometric-inertia sums, sleep
  // bookkeeping and recording. Its share of the call bounds what a second thread can win
  // (Amdahl).
  double serial_ms = 0.0;
};

}  // namespace softstep
