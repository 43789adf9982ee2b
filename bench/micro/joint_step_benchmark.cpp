// One whole step of a large scene of each new joint type, at scalar and AVX2 width, 1 thread:
// the kernels of the revolute, prismatic and weld joints reached through the public API
// (softstep_kernel_bench drives kernels directly and would need the solver's internals).
//
// BM_JointStep/type:T/simd:W, W 0 scalar, 1 AVX2 (skipped on a CPU without it):
//   T 0 revolute         100 hinge chains of 1,000 links, hinges only (5 rows)
//   T 1 revolute_all     the same with a +-170 degree limit, a friction motor and a 2 Hz spring
//   T 2 prismatic        10,000 stacks of 10 sliders, each with a 4 Hz spring and limits
//   T 3 weld             100 chains of 1,000 links welded, rigid point, 5 Hz angular spring
// 100,000 joints each. Counters: ms_per_step, and ns_per_row = step time / (the rows the plan
// runs per pass x sub-steps x passes), passes = solve iterations + relax iterations when the
// plan relaxes: the whole step's cost (bodies, prepare, store included) per row solved.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <numbers>
#include <optional>

#include "scenes/hinge_chain.hpp"
#include "scenes/prismatic_stack.hpp"

namespace softstep {
namespace {

constexpr double kDt = 1.0 / 60.0;
const char* const kTypeNames[] = {"revolute", "revolute_all", "prismatic", "weld"};

void build(World& world, int type) {
  if (type == 2) {
    scenes::PrismaticStackOptions o;
    o.columns = 10000;
    o.height = 10;
    scenes::build_prismatic_stack(world, o);
    return;
  }
  scenes::HingeChainOptions o;
  o.links = 1000;
  o.chains = 100;
  if (type == 1) {
    const double limit = 170.0 * std::numbers::pi / 180.0;
    o.limit = {true, -limit, limit};
    o.motor = {true, 0.0, 0.5};
    o.spring = {Spring::soft(2.0, 0.3), 0.0};
  }
  o.weld = type == 3;
  scenes::build_hinge_chain(world, o);
}

void BM_JointStep(benchmark::State& state) {
  const int type = static_cast<int>(state.range(0));
  WorldSettings s;
  s.threads = 1;       // per-core figures
  s.sleeping = false;  // every row solved in every step
  s.simd = state.range(1) == 0 ? SimdWidth::Scalar : SimdWidth::Avx2;
  std::optional<World> world;
  try {
    world.emplace(s);
  } catch (const InvalidArgument&) {
    state.SkipWithError("this CPU lacks AVX2");
    return;
  }
  build(*world, type);
  for (int i = 0; i < 3; ++i) world->step(kDt);  // pack, warm up
  for (auto _ : state) world->step(kDt);
  const StepPlan& plan = world->step_plan();
  const bool relaxed = plan.runs(PlanStage::Relax);
  const double passes = s.solve_iterations + (relaxed ? s.relax_iterations : 0);
  const double row_solves = static_cast<double>(plan.rows_per_pass) * s.substeps * passes;
  state.SetLabel(kTypeNames[type]);
  state.counters["joints"] = static_cast<double>(world->joint_count());
  state.counters["rows_per_joint"] =
      static_cast<double>(plan.rows_per_pass) / static_cast<double>(world->joint_count());
  state.counters["ms_per_step"] = benchmark::Counter(
      1e-3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_row"] =
      benchmark::Counter(row_solves * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                benchmark::Counter::kInvert);
}

BENCHMARK(BM_JointStep)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->ArgNames({"type", "simd"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
