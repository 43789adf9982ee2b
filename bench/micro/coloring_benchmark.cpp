// Coloring and lane packing, per constraint: from scratch (every constraint added in order),
// incremental (one constraint removed and added back in a built coloring) and packing every
// colour into 8-lane groups. Scenes: a chain of 100,000 links, 1,000 chains of 100 links, and
// the 316 x 316 joint grid (~200,000 joints).
#include <benchmark/benchmark.h>

#include <vector>

#include "softstep/graph_coloring/graph_coloring.hpp"

namespace softstep::graph_coloring {
namespace {

struct Edge {
  std::uint32_t a, b;
};

std::vector<Edge> chains(int links, int chain_length) {
  std::vector<Edge> e;
  for (int i = 0; i < links; ++i) {
    const bool first = i % chain_length == 0;
    e.push_back(
        {first ? kNonBlocking : static_cast<std::uint32_t>(i - 1), static_cast<std::uint32_t>(i)});
  }
  return e;
}

std::vector<Edge> grid(int n) {
  std::vector<Edge> e;
  const auto body = [&](int r, int c) {
    return r == 0 ? kNonBlocking : static_cast<std::uint32_t>(r * n + c);
  };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n && r > 0) e.push_back({body(r, c), body(r, c + 1)});
      if (r + 1 < n) e.push_back({body(r, c), body(r + 1, c)});
    }
  }
  return e;
}

std::vector<Edge> scene(int which) {
  if (which == 0) return chains(100000, 100000);
  if (which == 1) return chains(100000, 100);
  return grid(316);
}

const char* scene_name(int which) {
  return which == 0 ? "chain100k" : which == 1 ? "chains1000x100" : "grid316";
}

GraphColoring build(const std::vector<Edge>& edges) {
  GraphColoring g;
  for (std::uint32_t i = 0; i < edges.size(); ++i) g.add(i, edges[i].a, edges[i].b);
  return g;
}

void BM_ColorFromScratch(benchmark::State& state) {
  const auto edges = scene(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    GraphColoring g = build(edges);
    benchmark::DoNotOptimize(g.size());
  }
  state.SetLabel(scene_name(static_cast<int>(state.range(0))));
  state.counters["ns_per_constraint"] = benchmark::Counter(
      static_cast<double>(edges.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ColorIncremental(benchmark::State& state) {
  const auto edges = scene(static_cast<int>(state.range(0)));
  GraphColoring g = build(edges);
  std::uint32_t id = 0;
  for (auto _ : state) {
    g.remove(id);
    benchmark::DoNotOptimize(g.add(id, edges[id].a, edges[id].b));
    id = (id + 7919) % static_cast<std::uint32_t>(edges.size());
  }
  state.SetLabel(scene_name(static_cast<int>(state.range(0))));
  state.counters["ns_per_remove_add"] = benchmark::Counter(
      1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_PackLanes8(benchmark::State& state) {
  const auto edges = scene(static_cast<int>(state.range(0)));
  const GraphColoring g = build(edges);
  for (auto _ : state) {
    std::size_t lanes = 0;
    for (int c = 0; c < kColorCount; ++c) lanes += pack_lanes(g.members(c), 8, 0xFFFFFFFFu).size();
    benchmark::DoNotOptimize(lanes);
  }
  state.SetLabel(scene_name(static_cast<int>(state.range(0))));
  state.counters["ns_per_constraint"] = benchmark::Counter(
      static_cast<double>(edges.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_ColorFromScratch)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ColorIncremental)->DenseRange(0, 2);
BENCHMARK(BM_PackLanes8)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep::graph_coloring

BENCHMARK_MAIN();
