// The exact mode's tree solve alone (core/src/solver/tree_system.hpp): the factor, a solve of
// one right side (the solve pass) and of two (the relax pass: velocities and position
// projection together), and a factor with two right sides apart and in one sweep, on a chain
// of ball joints hanging from the world, 1,000 and 10,000 links. The figure to read is
// ns_per_row: CPU time per constraint row (3 per ball joint) for one factor or one solve, the
// same system again and again (hot in cache as far as it fits: 1,000 links do, 10,000 mostly
// not). Chains only: every body is a chain link, so the path of a body of many children (a
// ragdoll's torso) is not in these figures. Double precision, the same at every SIMD width:
// the chain's elimination is a sequence of dependent 3x3 steps.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "solver/tree_system.hpp"

namespace softstep::solver {
namespace {

// A ball joint's rows against one body: sign [I, -skew(r)].
Jac ball_rows(double sign, const Eigen::Vector3d& r) {
  Jac jac;
  jac << sign, 0.0, 0.0, 0.0, sign * r.z(), -sign * r.y(),  //
      0.0, sign, 0.0, -sign * r.z(), 0.0, sign * r.x(),     //
      0.0, 0.0, sign, sign * r.y(), -sign * r.x(), 0.0;
  return jac;
}

struct Chain {
  std::vector<TreeJoint> joints;
  std::vector<InverseMass> inverse_mass;
  std::vector<Eigen::Vector3d> second;  // the projection's right side
  TreeSystem system;

  explicit Chain(int links) : joints(links), inverse_mass(links), second(links) {
    std::mt19937 random(1);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    for (int j = 0; j < links; ++j) {
      TreeJoint& t = joints[static_cast<std::size_t>(j)];
      t.body[0] = j - 1;  // -1: the first joint holds body 0 to the world
      t.body[1] = j;
      const Eigen::Vector3d r_a(0.5 + jitter(random), jitter(random), jitter(random));
      const Eigen::Vector3d r_b(-0.5 + jitter(random), jitter(random), jitter(random));
      t.ball = true;
      t.jacobian[0] = ball_rows(-1.0, r_a);
      t.jacobian[1] = ball_rows(1.0, r_b);
      set_ball_arms(t);
      t.residual = {jitter(random), jitter(random), jitter(random)};
      second[static_cast<std::size_t>(j)] = {jitter(random), jitter(random), jitter(random)};
      InverseMass& w = inverse_mass[static_cast<std::size_t>(j)];
      w.linear = 1.0;
      w.angular = Eigen::Matrix3d::Identity() * (6.0 + jitter(random));
    }
    if (!system.build(static_cast<std::uint32_t>(links), joints)) std::abort();
    system.factor(inverse_mass, joints);
  }
};

void report_rows(benchmark::State& state, int links) {
  const double rows = 3.0 * links;
  state.counters["ns_per_row"] = benchmark::Counter(
      rows * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["rows"] = rows;
}

void factor(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  Chain chain(links);
  for (auto _ : state) {
    chain.system.factor(chain.inverse_mass, chain.joints);
    benchmark::ClobberMemory();
  }
  report_rows(state, links);
}

void solve_one_side(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  Chain chain(links);
  std::vector<Vec6> dv;
  std::vector<Eigen::Vector3d> dp;
  for (auto _ : state) {
    chain.system.solve(chain.joints, dv, dp);
    benchmark::DoNotOptimize(dp.data());
  }
  report_rows(state, links);
}

void solve_two_sides(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  Chain chain(links);
  std::vector<Vec6x2> dv;
  std::vector<Vec3x2> dp;
  for (auto _ : state) {
    chain.system.solve(chain.joints, chain.second, dv, dp);
    benchmark::DoNotOptimize(dp.data());
  }
  report_rows(state, links);
}

// A relax pass's factor and its two right sides, as the factor then the solve, and as the
// step's passes run them (TreeSystem::factor_solve_up: each node's forward step right after its
// elimination): the same bits, one sweep fewer.
void factor_then_solve_two_sides(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  Chain chain(links);
  std::vector<Vec6x2> dv;
  std::vector<Vec3x2> dp;
  for (auto _ : state) {
    chain.system.factor(chain.inverse_mass, chain.joints);
    chain.system.solve(chain.joints, chain.second, dv, dp);
    benchmark::DoNotOptimize(dp.data());
  }
  report_rows(state, links);
}

void factor_and_solve_two_sides_in_one_sweep(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  Chain chain(links);
  std::vector<Vec6x2> dv(static_cast<std::size_t>(links));
  std::vector<Vec3x2> dp(static_cast<std::size_t>(links));
  const MoreSides more = {&chain.second};
  for (auto _ : state) {
    chain.system.factor_solve_up<2>(0, chain.inverse_mass, chain.joints, more);
    chain.system.factor_solve_up<2>(1, chain.inverse_mass, chain.joints, more);
    chain.system.factor_solve_root<2>(chain.inverse_mass, chain.joints, dv, dp);
    chain.system.solve_down<2>(0, chain.joints, dv, dp);
    chain.system.solve_down<2>(1, chain.joints, dv, dp);
    benchmark::DoNotOptimize(dp.data());
  }
  report_rows(state, links);
}

BENCHMARK(factor)->Arg(1000)->Arg(10000);
BENCHMARK(solve_one_side)->Arg(1000)->Arg(10000);
BENCHMARK(solve_two_sides)->Arg(1000)->Arg(10000);
BENCHMARK(factor_then_solve_two_sides)->Arg(1000)->Arg(10000);
BENCHMARK(factor_and_solve_two_sides_in_one_sweep)->Arg(1000)->Arg(10000);

}  // namespace
}  // namespace softstep::solver

BENCHMARK_MAIN();
