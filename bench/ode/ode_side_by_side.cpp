// softstep beside ODE 0.16 (Debian's libode-dev, double precision) on the rigid chains of
// issue 14: N links of 1 kg (solid spheres, radius 0.1 m, 0.25 m apart) and an optional heavy
// ball at the end, laid out horizontally from a static anchor and released from rest, 60 Hz.
// Both engines build the same chain (scenes::build_chain's geometry); per setting it prints
// the worst stretch over the run ((sum of joint gaps) / rest length, the hard cases' measure),
// the worst single joint gap, and ms per step (the step calls only, one thread).
//
// ODE's settings: its direct solver (dWorldStep: the island's whole LCP, Dantzig's method,
// cubic in the rows) and its iterative one (dWorldQuickStep, SOR with 20 iterations), with
// ODE's default ERP 0.2 and CFM 1e-10, each at 1..16 sub-steps (dt / n per call). Optional:
// built only where pkg-config finds ODE; the library and the suite never need it.
#include <ode/ode.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/chain_scene.hpp"
#include "softstep/softstep.hpp"

namespace {

using softstep::scenes::ChainOptions;
using Clock = std::chrono::steady_clock;

struct Outcome {
  double worst_stretch = 0.0;  // (sum of joint gaps) / rest length, worst step
  double worst_gap = 0.0;      // m, any joint at any step
  double ms_per_step = 0.0;
  bool finite = true;
};

ChainOptions chain_options(int links, double ball) {
  ChainOptions o;
  o.link_masses.assign(static_cast<std::size_t>(links), 1.0);
  if (ball > 0.0) o.link_masses.push_back(ball);
  return o;
}

double rest_length(const ChainOptions& o) {
  return o.link_spacing * static_cast<double>(o.link_masses.size());
}

Outcome run_softstep(const ChainOptions& o, softstep::SolverMode mode, int substeps, int steps) {
  softstep::WorldSettings s;
  s.substeps = substeps;
  s.solver = mode;
  s.threads = 1;
  s.fixed_threads = true;
  s.sleeping = false;
  softstep::World world(s);
  const softstep::scenes::ChainScene scene = softstep::scenes::build_chain(world, o);
  Outcome out;
  double seconds = 0.0;
  for (int i = 0; i < steps; ++i) {
    const auto start = Clock::now();
    world.step(1.0 / 60.0);
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    double gaps = 0.0;
    for (softstep::JointId j : scene.joints) {
      const double gap = world.joint_reading(j).error;
      gaps += gap;
      out.worst_gap = std::max(out.worst_gap, gap);
    }
    out.finite = out.finite && std::isfinite(gaps);
    out.worst_stretch = std::max(out.worst_stretch, gaps / rest_length(o));
  }
  out.ms_per_step = 1e3 * seconds / steps;
  return out;
}

// The same chain in ODE: ball joints at the midpoints between centres, the first one to the
// static world at half a spacing from the anchor.
struct OdeChain {
  dWorldID world = dWorldCreate();
  std::vector<dJointID> joints;

  explicit OdeChain(const ChainOptions& o) {
    dWorldSetGravity(world, 0.0, -9.81, 0.0);
    dBodyID previous = nullptr;
    for (std::size_t i = 0; i < o.link_masses.size(); ++i) {
      const double x = o.link_spacing * static_cast<double>(i + 1);
      dBodyID body = dBodyCreate(world);
      dMass mass;
      dMassSetSphereTotal(&mass, o.link_masses[i], o.link_radius);
      dBodySetMass(body, &mass);
      dBodySetPosition(body, x, 0.0, 0.0);
      dJointID joint = dJointCreateBall(world, nullptr);
      dJointAttach(joint, previous, body);
      dJointSetBallAnchor(joint, x - 0.5 * o.link_spacing, 0.0, 0.0);
      joints.push_back(joint);
      previous = body;
    }
  }
  ~OdeChain() { dWorldDestroy(world); }
  OdeChain(const OdeChain&) = delete;
  OdeChain& operator=(const OdeChain&) = delete;

  double gap(dJointID joint) const {
    dVector3 on_a, on_b;
    dJointGetBallAnchor(joint, on_a);
    dJointGetBallAnchor2(joint, on_b);
    return std::sqrt((on_a[0] - on_b[0]) * (on_a[0] - on_b[0]) +
                     (on_a[1] - on_b[1]) * (on_a[1] - on_b[1]) +
                     (on_a[2] - on_b[2]) * (on_a[2] - on_b[2]));
  }
};

Outcome run_ode(const ChainOptions& o, bool direct, int substeps, int steps) {
  OdeChain chain(o);
  Outcome out;
  double seconds = 0.0;
  const double h = 1.0 / 60.0 / substeps;
  for (int i = 0; i < steps; ++i) {
    const auto start = Clock::now();
    for (int k = 0; k < substeps; ++k) {
      if (direct) {
        dWorldStep(chain.world, h);
      } else {
        dWorldQuickStep(chain.world, h);
      }
    }
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    double gaps = 0.0;
    for (dJointID j : chain.joints) {
      const double gap = chain.gap(j);
      gaps += gap;
      out.worst_gap = std::max(out.worst_gap, gap);
    }
    out.finite = out.finite && std::isfinite(gaps);
    out.worst_stretch = std::max(out.worst_stretch, gaps / rest_length(o));
    if (!out.finite) break;
  }
  out.ms_per_step = 1e3 * seconds / steps;
  return out;
}

// Both engines are deterministic: the runs differ only in time, whose median is kept.
template <class Run>
Outcome median_of_runs(int repeats, Run run) {
  std::vector<double> ms;
  Outcome out;
  for (int i = 0; i < repeats; ++i) {
    out = run();
    ms.push_back(out.ms_per_step);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  out.ms_per_step = ms[ms.size() / 2];
  return out;
}

void print_row(const char* engine, const char* solver, int substeps, const Outcome& r) {
  if (!r.finite) {
    std::printf("%-9s %-17s %9d %15s %12s %12.4f\n", engine, solver, substeps, "not finite", "-",
                r.ms_per_step);
    return;
  }
  std::printf("%-9s %-17s %9d %15.3g %12.3g %12.4f\n", engine, solver, substeps,
              100.0 * r.worst_stretch, r.worst_gap, r.ms_per_step);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "softstep beside ODE 0.16 on a horizontal rigid chain released from rest (issue 14): worst "
      "stretch, worst joint gap and ms per step for each solver and sub-step count"};
  int links = 10;
  double ball = 1000.0;
  int steps = 600;
  int direct_rows_max = 1500;
  int repeats = 5;
  std::vector<int> substeps{1, 2, 4, 8, 16};
  app.add_option("--links", links, "1 kg links (default 10)")->check(CLI::Range(1, 1000000));
  app.add_option("--ball", ball, "kg of the ball at the end, 0 for none (default 1000)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--steps", steps, "steps of 1/60 s (default 600: 10 s)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--substeps", substeps, "sub-step counts (default 1 2 4 8 16)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--repeats", repeats, "runs per setting; ms per step is their median (default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--ode-direct-rows-max", direct_rows_max,
                 "skip ODE's direct solver above this many rows: its time is cubic in them "
                 "(default 1500)");
  CLI11_PARSE(app, argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each row as it is measured, also into a file

  const ChainOptions o = chain_options(links, ball);
  const int rows = 3 * static_cast<int>(o.link_masses.size());
  std::printf("chain: %d x 1 kg links", links);
  if (ball > 0.0) std::printf(" + a %g kg ball", ball);
  std::printf(
      ", %d ball-joint rows, rest length %.2f m, %d steps of 1/60 s, one thread; ms per "
      "step: median of %d runs\n",
      rows, rest_length(o), steps, repeats);
  std::printf("%-9s %-17s %9s %15s %12s %12s\n", "engine", "solver", "substeps", "worst stretch %",
              "worst gap m", "ms/step");
  dInitODE2(0);
  for (int n : substeps) {
    const auto measured = [&](auto run) { return median_of_runs(repeats, run); };
    print_row("softstep", "iterative", n,
              measured([&] { return run_softstep(o, softstep::SolverMode::Iterative, n, steps); }));
    print_row("softstep", "direct-for-trees", n, measured([&] {
                return run_softstep(o, softstep::SolverMode::DirectForTrees, n, steps);
              }));
    if (rows <= direct_rows_max) {
      print_row("ODE", "dWorldStep", n, measured([&] { return run_ode(o, true, n, steps); }));
    } else {
      std::printf("%-9s %-17s %9d   skipped: %d rows > --ode-direct-rows-max\n", "ODE",
                  "dWorldStep", n, rows);
    }
    print_row("ODE", "dWorldQuickStep", n, measured([&] { return run_ode(o, false, n, steps); }));
  }
  dCloseODE();
  return 0;
}
