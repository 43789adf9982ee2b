// The machine's memory bandwidth, the bound a step of a large scene cannot beat: a STREAM-style
// triad a[i] = b[i] + s * c[i] over float arrays far larger than the last-level cache, on 1 and
// 2 threads (OpenMP, each thread its own contiguous slice, first touched by that thread).
// bytes_per_second counts what the loop itself names, 12 bytes per element (two reads, one
// write), as STREAM does; the write-allocate read of a[] that the cache adds is not counted, so
// the true traffic is up to 4/3 of it. An in-cache size beside it shows the gap.
//   softstep_bandwidth_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstddef>
#include <memory>

namespace softstep {
namespace {

struct FloatArray {
  explicit FloatArray(std::size_t n) : data(new float[n]) {}  // untouched: the threads touch it
  std::unique_ptr<float[]> data;
};

void BM_Triad(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  FloatArray a(n), b(n), c(n);
  float* pa = a.data.get();
  float* pb = b.data.get();
  float* pc = c.data.get();
  // First touch on the thread that will stream the slice (schedule(static) gives each thread
  // the same slice in every loop).
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) {
    pa[i] = 0.0f;
    pb[i] = 1.0f;
    pc[i] = 2.0f;
  }
  const float s = 3.0f;
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(3 * sizeof(float) * n));
  state.counters["threads"] = threads;
}

// (floats per array, threads): 3 x 64 MB arrays (DRAM), and 3 x 64 KB (in L2).
BENCHMARK(BM_Triad)
    ->ArgsProduct({{1 << 24, 1 << 14}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
