// Whether a large step runs on one thread or on all: decided from the wall times of recent
// steps, in trial blocks, so that a quiet second core is used and a busy one is left alone.
//
// What the first policy got wrong (issue 15): it judged two threads on step 0, which also
// colours and packs every joint, and later by single probe steps after 63 on one thread,
// each paying for body records that lived in the other core's cache; so two threads never won
// on a quiet machine. Here a step that rebuilt the plan is never timed, the first step after a
// switch is a warm-up that is not timed either, and a count is judged by the median of a block
// of steps. A probe that is clearly losing (a core held by another process) ends after its
// warm-up or its first timed step, and a lost probe doubles the interval to the next one, so
// contention costs a few slow steps per thousand.
#pragma once

#include <array>

namespace softstep {

class ThreadPolicy {
 public:
  // Timed steps per trial block (after the warm-up step).
  static constexpr int kTrialSteps = 4;
  static constexpr long kFirstProbeInterval = 64;
  static constexpr long kLongestProbeInterval = 1024;

  // True: the next step runs on all threads; false: on one.
  bool all_threads() const { return current_ == 1; }
  // The wall time of a step run as all_threads() said. `untimed`: the step rebuilt the
  // plan (colouring, packing), so its time says nothing about the thread count.
  void record(double ms, bool untimed);
  // How often the count changed (probes and their returns included).
  long switches() const { return switches_; }
  // New content (bodies, joints, sleep): measure both counts afresh; the switch count stays.
  void restart() {
    const long switches = switches_;
    *this = ThreadPolicy{};
    switches_ = switches;
  }

 private:
  void switch_count();
  void decide_probe();

  int current_ = 1;  // 1: all threads, 0: one; the first block measures all threads
  bool probing_ = true;
  std::array<double, 2> estimate_{0.0, 0.0};  // ms per step of each count, 0: unknown
  std::array<double, kTrialSteps> samples_{};
  int sampled_ = 0;      // timed steps in the current block
  bool warmed_ = false;  // the current block's warm-up step has run
  long settled_steps_ = 0;
  long probe_interval_ = kFirstProbeInterval;
  long switches_ = 0;
};

}  // namespace softstep
