// What the public API's calls cost outside the step (issue 17: create_body took 8-9 us, most
// of it formatting error messages for checks that passed; the target is under 0.3 us).
//
// BM_CreateBody/<kind>/<reuse>: creates 10,000 bodies per iteration; counter us_per_body.
//   kind 0: dynamic, diagonal inertia (the common case); 1: dynamic, a full symmetric tensor
//   (validated with the eigensolver); 2: static (no mass checks).
//   reuse 0: into a fresh world (building and destroying it is not timed; growing its storage
//   is, page faults included); reuse 1: into the slots of 10,000 bodies just destroyed (the
//   call alone, as in a game that streams bodies in and out).
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

void BM_CreateBody(benchmark::State& state) {
  constexpr int kBodies = 10000;
  BodyDef def;
  if (state.range(0) == 1) {
    def.inertia << 0.004, 0.001, 0.0, 0.001, 0.004, 0.0005, 0.0, 0.0005, 0.004;
  } else if (state.range(0) == 2) {
    def.type = BodyType::Static;
  }
  const bool reuse = state.range(1) == 1;
  std::vector<BodyId> ids(kBodies);
  auto world = std::make_unique<World>();
  for (auto _ : state) {
    state.PauseTiming();
    if (reuse) {
      if (world->body_count() == 0) {
        for (int i = 0; i < kBodies; ++i)
          ids[static_cast<std::size_t>(i)] = world->create_body(def);
      }
      for (BodyId id : ids) world->destroy_body(id);
    } else {
      world = std::make_unique<World>();
    }
    state.ResumeTiming();
    for (int i = 0; i < kBodies; ++i) {
      def.position.x() = 0.25 * i;
      ids[static_cast<std::size_t>(i)] = world->create_body(def);
    }
    benchmark::ClobberMemory();
  }
  state.counters["us_per_body"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kBodies * 1e-6,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CreateBody)
    ->ArgNames({"kind", "reuse"})
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
