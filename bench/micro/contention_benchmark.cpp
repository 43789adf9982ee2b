// Steps of a chain with 1 and 2 threads while a competing busy thread spins on the machine
// (standing in for another process holding a core, as on a shared CI machine or a game's
// own threads), and without it. Compare 2-thread/1-thread under load: the bound is
// 1.5x. Run the variants interleaved:
//   softstep_contention_bench --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true
#include <benchmark/benchmark.h>

#include <atomic>
#include <optional>
#include <thread>

#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

class BusyThread {
 public:
  BusyThread()
      : thread_([this] {
          volatile unsigned x = 0;
          while (!stop_.load(std::memory_order_relaxed)) x = x + 1;
        }) {}
  ~BusyThread() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

void step_chain(benchmark::State& state, bool busy) {
  WorldSettings s;
  s.threads = static_cast<int>(state.range(1));
  World world(s);
  scenes::ChainOptions o;
  o.links = 1000;
  o.chains = static_cast<int>(state.range(0)) / 1000;
  o.spring = Spring::soft(30.0, 0.7);
  scenes::build_chain(world, o);
  world.step(1.0 / 60.0);
  std::optional<BusyThread> competitor;
  if (busy) competitor.emplace();
  for (auto _ : state) world.step(1.0 / 60.0);
  state.counters["ms_per_step"] = benchmark::Counter(
      1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_StepQuiet(benchmark::State& state) {
  step_chain(state, false);
}
void BM_StepUnderLoad(benchmark::State& state) {
  step_chain(state, true);
}

// (links, threads)
BENCHMARK(BM_StepQuiet)
    ->ArgsProduct({{10000, 100000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_StepUnderLoad)
    ->ArgsProduct({{10000, 100000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
