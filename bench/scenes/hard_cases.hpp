// The hard cases: scenes that push the solver to its limits (mass ratios, stiffness, long
// chains, violated starts, big steps, degenerate geometry), each with the figures it is
// judged by and the bounds it must stay within. One definition serves the test suite
// (tests/hard_cases_test.cpp) and the report (`softstep hardcases`), so the table in the
// README is what the tests assert.
//
// The bounds are derived, not fitted. The one that recurs: a rigid row is solved as a stiff
// spring of angular frequency omega = 2 pi min(rigid_hertz, substep_rate / 4), and a joint at
// rest under tension T stretches T / (m_eff omega^2) (tests/hanging_chain_test.cpp). A load
// applied at once to an undamped spring overshoots to twice its static stretch, so a joint's
// error is bounded by 3x its static stretch (2x and a margin); a body cannot be faster than a
// free fall through twice the chain's total static stretch (energy), plus what it started with.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::scenes {

struct HardCaseFigures {
  bool finite = true;        // no NaN or inf in any body state at any sampled step
  double joint_error = 0.0;  // m: largest joint error (over the run, or at its end: see the case)
  double max_speed = 0.0;    // m/s: fastest body at any sampled step
  double energy_gain = 0.0;  // (max E(t) - E(0)) / E_ref: energy the solver created, relative
};

struct HardCaseBounds {
  double joint_error;  // m
  double max_speed;    // m/s
  double energy_gain;  // fraction of E_ref
};

struct HardCaseOutcome {
  HardCaseFigures figures;
  HardCaseBounds bounds;  // derived for the settings the case ran with
  bool passed() const;
};

struct HardCase {
  std::string name;
  std::string parameters;
  bool heavy = false;  // long-running: the tests run it at one width (widths are bit-identical)
  std::function<HardCaseOutcome(const WorldSettings& base)> run;
  // Non-empty: a known failure, with its cause. The report shows the case; the tests skip it
  // with this reason until the solver handles it.
  std::string known_failure = {};
};

std::vector<HardCase> hard_cases();

// Sees the world of every hard case before its first step (step 0) and after each step (the
// tool's `hardcases --view` records them). A case that runs several worlds in turn shows each
// from step 0. Applies to cases run on the calling thread; empty: none (the default).
using HardCaseWatcher = std::function<void(World& world, long step, double dt)>;
void watch_hard_cases(HardCaseWatcher watcher);

// Static stretch of each joint of a chain hanging at rest from a static anchor, ball joints
// on the chain's axis, links of the given masses (top first): T_i / (m_eff_i omega^2).
std::vector<double> hanging_chain_stretch(const std::vector<double>& masses, double gravity,
                                          double omega);

}  // namespace softstep::scenes
