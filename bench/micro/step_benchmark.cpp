// One step of a chain, 1,000 and 10,000 links, rigid and soft ball joints, 60 Hz, 4 sub-steps,
// 1 relax. Counters: ms per step and ns per row solve (rows x (1 solve + relax passes) x
// sub-steps).
#include <benchmark/benchmark.h>

#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

void step_chain(benchmark::State& state, SimdWidth width, bool soft) {
  WorldSettings s;
  s.simd = width;
  s.threads = 1;  // these figures are per core; softstep_contention_bench compares thread counts
  World world(s);
  scenes::ChainOptions o;
  o.links = static_cast<int>(state.range(0));
  if (soft) o.spring = Spring::soft(10.0, 0.7);
  scenes::build_chain(world, o);
  world.step(1.0 / 60.0);  // pack and warm up
  for (auto _ : state) world.step(1.0 / 60.0);
  const double row_solves = 3.0 * o.links * s.substeps * (1 + s.relax_iterations);
  state.counters["ms_per_step"] = benchmark::Counter(
      1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_row"] =
      benchmark::Counter(row_solves * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                benchmark::Counter::kInvert);
}

void BM_ChainStepRigid(benchmark::State& state) {
  step_chain(state, SimdWidth::Best, false);
}
void BM_ChainStepSoft(benchmark::State& state) {
  step_chain(state, SimdWidth::Best, true);
}
void BM_ChainStepRigidScalar(benchmark::State& state) {
  step_chain(state, SimdWidth::Scalar, false);
}

BENCHMARK(BM_ChainStepRigid)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ChainStepSoft)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ChainStepRigidScalar)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
