// What the public API's calls cost outside the step (issue 17: create_body took 8-9 us, most
// of it formatting error messages for checks that passed; the target is under 0.3 us).
//
// BM_CreateBody/<kind>/<reuse>: creates 10,000 bodies per iteration; counter us_per_body.
//   kind 0: dynamic, diagonal inertia (the common case); 1: dynamic, a full symmetric tensor
//   (validated with the eigensolver); 2: static (no mass checks).
//   reuse 0: into a fresh world (building and destroying it is not timed; growing its storage
//   is, page faults included); reuse 1: into the slots of 10,000 bodies just destroyed (the
//   call alone, as in a game that streams bodies in and out); reuse 2: into a fresh world
//   that World::reserve made room in (untimed): the first touch of fresh pages, no copies.
//
// BM_DestroyJointAfterStep/<joints>: a hanging chain of <joints> ball joints, stepped once; each
//   iteration destroys the joint at the chain's free end and steps again. Counters: us_destroy
//   (the call) and ms_step (the step after it), beside BM_StepAlone/<joints> (the same step with
//   nothing destroyed). Issue 17: the first destroy after a step cost time proportional to the
//   world (3.3 ms at 100,000 joints) and the next step re-packed every joint.
#include <benchmark/benchmark.h>

#include <chrono>
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
      if (state.range(1) == 2) world->reserve(kBodies, 0);
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
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// A hanging chain of `links` bodies on ball joints from a static anchor; sleeping off so every
// step solves the whole chain.
std::unique_ptr<World> hanging_chain(int links, std::vector<JointId>& joints) {
  WorldSettings settings;
  settings.sleeping = false;
  auto world = std::make_unique<World>(settings);
  world->reserve(static_cast<std::size_t>(links) + 1, static_cast<std::size_t>(links));
  BodyDef anchor;
  anchor.type = BodyType::Static;
  BodyId previous = world->create_body(anchor);
  joints.clear();
  for (int i = 0; i < links; ++i) {
    BodyDef link;
    link.position = {0.0, -0.1 * (i + 1), 0.0};
    const BodyId body = world->create_body(link);
    BallJointDef joint;
    joint.body_a = previous;
    joint.body_b = body;
    joint.local_anchor_a = {0.0, i == 0 ? 0.0 : -0.05, 0.0};
    joint.local_anchor_b = {0.0, 0.05, 0.0};
    joints.push_back(world->create_joint(joint));
    previous = body;
  }
  return world;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void BM_DestroyJointAfterStep(benchmark::State& state) {
  std::vector<JointId> joints;
  auto world = hanging_chain(static_cast<int>(state.range(0)), joints);
  world->step(1.0 / 60.0);
  double destroy_s = 0.0, step_s = 0.0;
  for (auto _ : state) {
    if (joints.empty()) state.SkipWithError("chain used up");
    const auto t0 = Clock::now();
    world->destroy_joint(joints.back());
    destroy_s += seconds_since(t0);
    joints.pop_back();
    const auto t1 = Clock::now();
    world->step(1.0 / 60.0);
    step_s += seconds_since(t1);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["us_destroy"] = destroy_s / n * 1e6;
  state.counters["ms_step"] = step_s / n * 1e3;
}
BENCHMARK(BM_DestroyJointAfterStep)
    ->ArgName("joints")
    ->Arg(100000)
    ->Iterations(20)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_StepAlone(benchmark::State& state) {
  std::vector<JointId> joints;
  auto world = hanging_chain(static_cast<int>(state.range(0)), joints);
  world->step(1.0 / 60.0);
  double step_s = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    world->step(1.0 / 60.0);
    step_s += seconds_since(t0);
  }
  state.counters["ms_step"] = step_s / static_cast<double>(state.iterations()) * 1e3;
}
BENCHMARK(BM_StepAlone)
    ->ArgName("joints")
    ->Arg(100000)
    ->Iterations(20)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softstep

BENCHMARK_MAIN();
