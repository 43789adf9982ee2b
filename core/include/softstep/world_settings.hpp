#pragma once

#include <Eigen/Core>
#include <numbers>

#include "softstep/contacts.hpp"

namespace softstep {

// Lane width of the solver kernels. All widths give bit-identical results.
enum class SimdWidth {
  Best,    // the widest this CPU and build support
  Scalar,  // 1 lane
  Sse,     // 4 lanes, SSE4.2
  Avx2,    // 8 lanes, AVX2
  Avx512,  // 16 lanes, AVX-512 (F, CD, DQ, BW, VL: x86-64-v4)
};

// "best", "scalar", "sse", "avx2" or "avx512".
const char* simd_width_name(SimdWidth width);

// How the joints of each island are solved (README, "Rigid means rigid").
enum class SolverMode {
  // Gauss-Seidel passes over soft rows (the design's default): a rigid row is a stiff spring
  // of at most a quarter of the sub-step rate, so a chain under a heavy load stretches.
  Iterative,
  // Islands whose joints form a tree (chains, ropes, ragdolls, bridges: no loop through movable
  // bodies) and are all rigid ball or rigid distance joints are solved exactly each sub-step,
  // in time linear in their rows, with rigid rows that are rigid (no softness): the load no
  // longer stretches them. Every other island is solved iteratively, as in Iterative. Their
  // positions are projected back onto the joints in the relax pass, so relax_iterations = 0
  // also drops that (the 1,000-link whip then opens 0.16 m at 1 sub-step, 1e-6 m with it).
  DirectForTrees,
  // As DirectForTrees, except islands of a single joint, which one Gauss-Seidel pass already
  // solves exactly (a block solve of their one joint).
  Auto,
};

// "iterative", "direct-for-trees" or "auto".
const char* solver_mode_name(SolverMode mode);

struct WorldSettings {
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  int substeps = 4;                          // >= 1: sub-steps per step(dt), each a full solve
  // >= 1: biased Gauss-Seidel passes per sub-step. One is the design's choice (sub-steps buy
  // accuracy more cheaply than iterations, DESIGN.md); more converge each sub-step towards
  // the exact solution of its soft system, which `softstep sweep` measures.
  int solve_iterations = 1;
  // >= 0: rigid, unbiased passes per sub-step after positions move. 0 leaves the rigid rows'
  // position correction in the velocities: a weld or prismatic turning a body back from far
  // off its pose then overshoots, and flings a body of moments 1e3 or more apart (README,
  // "Settings that trade time for accuracy").
  int relax_iterations = 1;
  // Threads a step may use: 0 = all of the machine's cores (the default), or a count >= 1.
  // Steps with fewer than 4,096 bodies and joints run on one thread, and larger ones use one
  // or all, whichever ran recent steps faster (see README). Results are bit-identical for
  // any count.
  int threads = 0;
  // true: every step runs on exactly `threads` threads (0: all of the machine's cores),
  // however small the step and however recent steps ran; for a host that has set its cores
  // aside for the physics, or to measure. false: the adaptive choice above.
  bool fixed_threads = false;
  bool warm_start = true;  // start each sub-step from the previous sub-step's impulses
  // Rigid rows are solved as a stiff spring (and relaxed with none). Its frequency is capped
  // at a quarter of the sub-step rate, so it cannot overshoot: Hz, > 0.
  double rigid_hertz = 60.0;
  double rigid_damping_ratio = 2.0;  // >= 0
  // How fast a rigid row may correct position error, m/s, > 0: joints created apart close
  // at this speed instead of launching bodies.
  double max_correction_speed = 3.0;
  // Stabilizes the alignment mode of bodies hinged off their centre under tension: a link
  // hinged at r from its centre under tension T turns like a spring of frequency
  // sqrt(T r / I), which a sub-step h can only follow while h sqrt(T r / I) < 2 (long chains,
  // light links and big steps cross it and blow up). When on, each body's inertia in the
  // solver is raised by h^2 sum(|F| |r|) over its joints (the diagonal geometric stiffness of
  // Andrews, Teichmann and Kry 2017), which keeps that mode below 1/h and changes nothing
  // where it was resolved. Joint forces are the previous step's. Sub-steps finer than 1/240 s
  // (60 Hz with 4 sub-steps) use (1/240 s)^2 instead of h^2: finer sub-steps must not take
  // the stabilization away (README, "The alignment mode").
  bool geometric_stiffness = true;
  // Bodies move no faster than this, m/s, in (0, 1e6]: the solver clamps dynamic bodies' speed
  // each sub-step, as velocities are integrated and again before positions move (the relax
  // pass after that may leave a velocity above it, which the next sub-step clamps), and
  // rejects a velocity above it. It keeps the float solver's products in
  // range (README, "Input ranges"); 10 km/s is above anything a game throws.
  double max_linear_speed = 1e4;
  // The spin limit: a dynamic body turns at most this far per sub-step, rad, in (0, pi/2];
  // default pi/4, an eighth of a turn. Beyond it the solver's first-order rotation update is
  // meaningless and an anchor off the centre swings anywhere (links of tiny inertia and chains
  // at 1/15 s steps blew up without it). It bounds the angular speed to
  // max_rotation_per_substep * substeps / dt each sub-step, as max_linear_speed bounds the
  // linear one, kinematic bodies included. Unlike that fixed speed it depends on the step, so
  // an angular velocity you set is not rejected: it is clamped. At the defaults (4 sub-steps
  // of a 1/60 s step) it is 188.5 rad/s, at 1 sub-step 47 rad/s: a 0.35 m wheel at 47 rad/s
  // rolls at 59 km/h. A wheel of radius r at speed v needs
  // v / r <= max_rotation_per_substep * substeps / dt: raise the sub-steps, or this to pi/2.
  double max_rotation_per_substep = 0.25 * std::numbers::pi;
  SimdWidth simd = SimdWidth::Best;
  // Iterative, DirectForTrees or Auto (above). World::step_plan shows which islands ran which.
  SolverMode solver = SolverMode::Iterative;
  // Sleeping. An island (bodies linked by joints; a static body links nothing) whose bodies
  // all stay below both speeds for time_to_sleep falls asleep: its bodies stop (velocity 0)
  // and cost nothing per step until something wakes it (README, "Sleeping").
  bool sleeping = true;
  double sleep_linear_speed = 0.05;   // m/s, >= 0
  double sleep_angular_speed = 0.05;  // rad/s, >= 0
  double time_to_sleep = 0.5;         // s, >= 0
  // Each joint runs the kernel compiled for exactly its features and the step leaves out the
  // stages the scene has no use for (World::step_plan). false: every joint runs the general
  // kernel and every stage runs, fed neutral values: the baseline the benchmarks compare
  // with. Both give the same results (up to the sign of a zero).
  bool specialize = true;
  // How the contacts given to step() are solved (contacts.hpp).
  ContactSettings contact{};
};

// Whether the contact solve passes run the friction rows: as contact.friction_while_solving
// asks, except where friction relaxed only would not carry into the next sub-step (no relax
// pass to run it in, or no warm start to bring its impulse into the next solve pass).
inline bool contact_friction_while_solving(const WorldSettings& s) {
  return s.contact.friction_while_solving || s.relax_iterations == 0 || !s.warm_start;
}

}  // namespace softstep
