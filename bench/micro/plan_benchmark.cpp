// What the step plan saves. Two families, both stepping whole worlds through the public API
// on one thread (figures per core):
//
// BM_Effect/<scene>/<specialized>: a 10,000-link chain lacking some effects, stepped by the
//   specialized plan (1) and by the general kernels with every stage fed neutral values (0):
//   zero gravity added, damping factor 1, a rigid lane's per-lane switches, a disabled limit
//   row's zero impulse, a free spring's zero row. Counters: ms per step and ns per row (rows
//   the scene really has x sub-steps x passes).
//   Compare the two with --benchmark_enable_random_interleaving=true and repetitions.
//
// BM_SleepingChains/<asleep>: 100 chains of 1,000 links in zero gravity; one is kept moving.
//   asleep = 1: the other 99 came to rest and sleep; asleep = 0: sleeping is off, all 100 are
//   solved (the same motion). The ratio of the two is what sleeping saves.
#include <benchmark/benchmark.h>

#include <string>

#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

constexpr double kDt = 1.0 / 60.0;

struct EffectScene {
  const char* name;  // the effects it lacks
  scenes::ChainJoint joint;
  Spring spring;
  bool gravity;
  double max_length;  // distance joints
  int rows;           // per joint the scene really has
};

const EffectScene kScenes[] = {
    {"no_springs_damping_limits", scenes::ChainJoint::Ball, Spring::rigid(), true,
     std::numeric_limits<double>::infinity(), 3},
    {"no_gravity_springs_damping_limits", scenes::ChainJoint::Ball, Spring::rigid(), false,
     std::numeric_limits<double>::infinity(), 3},
    {"no_rigid_rows_damping_limits", scenes::ChainJoint::Ball, Spring::soft(10.0, 0.7), true,
     std::numeric_limits<double>::infinity(), 3},
    {"distance_no_limits_springs", scenes::ChainJoint::Distance, Spring::rigid(), true,
     std::numeric_limits<double>::infinity(), 1},
    {"distance_spring_no_limits", scenes::ChainJoint::Distance, Spring::soft(10.0, 0.7), true,
     std::numeric_limits<double>::infinity(), 1},
    {"rope_no_spring_row_no_min", scenes::ChainJoint::Distance, Spring::free(), true, 0.25, 1},
};

void BM_Effect(benchmark::State& state) {
  const EffectScene& scene = kScenes[state.range(0)];
  WorldSettings s;
  s.threads = 1;
  s.sleeping = false;  // the chain swings for the whole run anyway; keep every row solved
  s.specialize = state.range(1) != 0;
  if (!scene.gravity) s.gravity.setZero();
  World world(s);
  scenes::ChainOptions o;
  o.links = 10000;
  o.joint = scene.joint;
  o.spring = scene.spring;
  o.max_length = scene.max_length;
  const scenes::ChainScene built = scenes::build_chain(world, o);
  if (!scene.gravity) {
    // Something to solve in zero gravity: the chain spins about its anchor.
    for (BodyId b : built.links[0]) {
      world.set_linear_velocity(b, {0.0, 0.0, 0.5 * world.body(b).position.x()});
    }
  }
  for (int i = 0; i < 3; ++i) world.step(kDt);  // pack, warm up
  for (auto _ : state) world.step(kDt);
  state.SetLabel(scene.name);
  const double passes = s.solve_iterations + s.relax_iterations;
  const double row_solves = double(scene.rows) * o.links * s.substeps * passes;
  state.counters["ms_per_step"] = benchmark::Counter(
      1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_row"] =
      benchmark::Counter(row_solves * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                benchmark::Counter::kInvert);
}

void BM_SleepingChains(benchmark::State& state) {
  const bool sleeping = state.range(0) != 0;
  WorldSettings s;
  s.threads = 1;
  s.gravity.setZero();
  s.sleeping = sleeping;
  World world(s);
  scenes::ChainOptions o;
  o.links = 1000;
  o.chains = 100;
  const scenes::ChainScene built = scenes::build_chain(world, o);
  // Chain 0 keeps moving: it spins about its anchor in zero gravity, and never stops.
  for (BodyId b : built.links[0]) {
    world.set_linear_velocity(b, {0.0, 0.0, 0.5 * world.body(b).position.x()});
  }
  // The other 99 rest from the start: after time_to_sleep (0.5 s) they sleep.
  for (int i = 0; i < 40; ++i) world.step(kDt);
  if (sleeping && world.step_plan().sleeping_islands != 99) {
    state.SkipWithError("the 99 resting chains did not fall asleep");
  }
  for (auto _ : state) world.step(kDt);
  state.counters["awake_bodies"] = static_cast<double>(world.step_plan().awake_bodies);
  state.counters["ms_per_step"] = benchmark::Counter(
      1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Effect)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1}})
    ->ArgNames({"scene", "specialized"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SleepingChains)->Arg(0)->Arg(1)->ArgName("asleep")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
