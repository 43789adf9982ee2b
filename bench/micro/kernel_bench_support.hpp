// What the kernel benchmarks share: chains packed into lane groups the way the solver packs them,
// one kernel pass per stage, and the ns-per-row counter. Included by kernel_benchmark.cpp (scalar,
// SSE, AVX2) and kernel_benchmark_avx512.cpp (compiled for AVX-512): everything here has internal
// linkage, so neither file's copy, compiled for its own instruction set, can stand in for the
// other's.
#pragma once

#include <benchmark/benchmark.h>

#include <vector>

#include "softstep/graph_coloring/graph_coloring.hpp"
#include "softstep/simd/ball_joint_kernel.hpp"
#include "softstep/simd/distance_joint_kernel.hpp"
#include "softstep/simd/prismatic_joint_kernel.hpp"
#include "softstep/simd/motor_joint_kernel.hpp"
#include "softstep/simd/revolute_joint_kernel.hpp"
#include "softstep/simd/swing_twist_joint_kernel.hpp"
#include "softstep/simd/weld_joint_kernel.hpp"
#include "softstep/simd/wheel_joint_kernel.hpp"

namespace softstep::simd {
namespace {

constexpr float kSpacing = 0.25f;

// Chains along x: link j of chain c is body 1 + c * links + j; the first joint of a chain
// hangs from the static dummy (body 0).
struct Bodies {
  std::vector<VelocityRecord> velocity;
  std::vector<DeltaRecord> delta;
  std::vector<MassRecord> mass;
  BodyArrays arrays() { return {velocity.data(), delta.data(), mass.data()}; }
};

Bodies make_bodies(int count) {
  Bodies b;
  b.velocity.assign(static_cast<std::size_t>(count) + 1,
                    VelocityRecord{{0.0f, -0.1f, 0.0f}, {0.0f, 0.0f, 0.3f}, {}});
  b.delta.assign(static_cast<std::size_t>(count) + 1, DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0});
  b.mass.assign(static_cast<std::size_t>(count) + 1, MassRecord{1.0f, {250, 250, 250, 0, 0, 0}, 0});
  b.velocity[0] = VelocityRecord{};
  b.mass[0] = MassRecord{};
  return b;
}

template <template <int> class Group, int W>
struct Packed {
  std::vector<std::vector<Group<W>>> colors;
  Bodies bodies;
  std::size_t joints = 0;
};

template <template <int> class Group, int W>
Packed<Group, W> pack_chains(int total_links, int chain_length) {
  Packed<Group, W> p;
  p.bodies = make_bodies(total_links);
  graph_coloring::GraphColoring coloring;
  std::vector<std::pair<std::int32_t, std::int32_t>> ends;
  for (int i = 0; i < total_links; ++i) {
    const bool first = i % chain_length == 0;
    const std::int32_t a = first ? 0 : i;  // body i is link i-1 (bodies start at 1)
    const std::int32_t b = i + 1;
    ends.emplace_back(a, b);
    coloring.add(static_cast<std::uint32_t>(i),
                 first ? graph_coloring::kNonBlocking : static_cast<std::uint32_t>(a),
                 static_cast<std::uint32_t>(b));
  }
  p.joints = ends.size();
  for (int c = 0; c < graph_coloring::kColorCount; ++c) {
    if (coloring.members(c).empty()) continue;
    const auto lanes = graph_coloring::pack_lanes(coloring.members(c), W, 0xFFFFFFFFu);
    auto& groups = p.colors.emplace_back(lanes.size() / W, Group<W>{});
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      Group<W>& g = groups[i / W];
      const int lane = static_cast<int>(i % W);
      if (lanes[i] == 0xFFFFFFFFu) continue;  // padding: dummy bodies, free spring
      const auto [a, b] = ends[lanes[i]];
      g.body_a[lane] = a;
      g.body_b[lane] = b;
      g.r_a[0][lane] = 0.5f * kSpacing;
      g.r_b[0][lane] = -0.5f * kSpacing;
      g.center_delta[0][lane] = kSpacing * 1.01f;  // a little stretched: the bias is not zero
      if constexpr (requires { g.hertz; }) g.hertz[lane] = kRigidHertz;
      if constexpr (requires { g.rest_length; }) {
        g.r_a[0][lane] = g.r_b[0][lane] = 0.0f;
        g.rest_length[lane] = kSpacing;
        g.max_length[lane] = kSpacing;
      }
      if constexpr (requires { g.frame_a; }) {  // frames at identity: hinge or slide along z
        g.frame_a[3][lane] = g.frame_b[3][lane] = 1.0f;
      }
      if constexpr (requires { g.inv_cone_x_sq; }) {  // B leaning 0.3 rad in a 0.5 rad cone
        g.frame_b[0][lane] = 0.1494381f;                // sin(0.15): turned about x
        g.frame_b[3][lane] = 0.9887711f;
        g.target_a[3][lane] = 1.0f;
        g.inv_cone_x_sq[lane] = g.inv_cone_y_sq[lane] = 16.32f;  // 1 / sin^2(0.25)
        g.twist_lower[lane] = -0.5f;
        g.twist_upper[lane] = 0.5f;
        g.motor_max[lane] = 1.0f;
        g.spring.hertz[lane] = 2.0f;
        g.spring.zeta[lane] = 0.5f;
      }
      if constexpr (requires { g.steer_cos; }) {  // a wheel: straight ahead, 10 kg sprung
        g.steer_cos[lane] = 1.0f;
        g.sprung_mass[lane] = 10.0f;
      }
      if constexpr (requires { g.max_force; }) {  // a motor joint: caps, springs when soft
        g.max_force[lane] = 100.0f;
        g.max_torque[lane] = 10.0f;
        g.linear.hertz[lane] = g.angular.hertz[lane] = 2.0f;
        g.linear.zeta[lane] = g.angular.zeta[lane] = 1.0f;
      }
      if constexpr (requires { g.axis; }) {  // limits around 0, a motor and a spring
        g.axis.lower_gap[lane] = 0.5f;
        g.axis.upper_gap[lane] = 0.5f;
        g.axis.motor_speed[lane] = 1.0f;
        g.axis.motor_max[lane] = 10.0f;
        g.axis.spring_hertz[lane] = 2.0f;
        g.axis.spring_zeta[lane] = 0.5f;
      }
    }
  }
  return p;
}

const SubstepContext kContext{1.0f / 240.0f,
                              240.0f,
                              make_softness(60.0f, 2.0f, 1.0f / 240.0f),
                              make_softness(120.0f, 2.0f, 1.0f / 240.0f),
                              3.0f,
                              1e4f,
                              0.25f * 3.14159265f * 240.0f};

enum class Stage { Prepare, WarmStart, Solve, Relax };

// One kernel's passes over one group, and its rows per joint with signature `sig`.
template <template <int> class Group>
struct Kernel;
template <>
struct Kernel<BallJointGroup> {
  template <class L, JointFeatures F, Stage S>
  static void run(BallJointGroup<kWidth<L>>& g, const BodyArrays& b, std::uint32_t) {
    if constexpr (S == Stage::Prepare) prepare_ball_joints<L, F>(g, kContext);
    if constexpr (S == Stage::WarmStart) warm_start_ball_joints<L, F>(g, b);
    if constexpr (S == Stage::Solve) solve_ball_joints<L, true, F>(g, b);
    if constexpr (S == Stage::Relax) solve_ball_joints<L, false, F>(g, b);
  }
  static double rows(std::uint32_t) { return 3.0; }
};
template <>
struct Kernel<DistanceJointGroup> {
  template <class L, JointFeatures F, Stage S>
  static void run(DistanceJointGroup<kWidth<L>>& g, const BodyArrays& b, std::uint32_t) {
    if constexpr (S == Stage::Prepare) prepare_distance_joints<L, F>(g, kContext);
    if constexpr (S == Stage::WarmStart) warm_start_distance_joints<L, F>(g, b);
    if constexpr (S == Stage::Solve) solve_distance_joints<L, true, F>(g, b, kContext);
    if constexpr (S == Stage::Relax) solve_distance_joints<L, false, F>(g, b, kContext);
  }
  static double rows(std::uint32_t) { return 1.0; }
};
// The angular types: one kernel, parts by signature.
#define SOFTSTEP_ANGULAR_KERNEL(GROUP, NAME, ROWS)                                           \
  template <>                                                                                \
  struct Kernel<GROUP> {                                                                     \
    template <class L, JointFeatures, Stage S>                                               \
    static void run(GROUP<kWidth<L>>& g, const BodyArrays& b, std::uint32_t sig) {           \
      if constexpr (S == Stage::Prepare) prepare_##NAME##_joints<L>(g, kContext, sig);       \
      if constexpr (S == Stage::WarmStart) warm_start_##NAME##_joints<L>(g, b, sig);         \
      if constexpr (S == Stage::Solve) solve_##NAME##_joints<L, true>(g, b, kContext, sig);  \
      if constexpr (S == Stage::Relax) solve_##NAME##_joints<L, false>(g, b, kContext, sig); \
    }                                                                                        \
    static double rows(std::uint32_t sig) { return ROWS; }                                   \
  }
constexpr std::uint32_t kAllAxisParts = kAxisLimit | kAxisMotor | kAxisSpring;
SOFTSTEP_ANGULAR_KERNEL(RevoluteJointGroup, revolute, sig == 0 ? 5.0 : 9.0);
SOFTSTEP_ANGULAR_KERNEL(PrismaticJointGroup, prismatic, sig == 0 ? 5.0 : 9.0);
SOFTSTEP_ANGULAR_KERNEL(WeldJointGroup, weld, (void(sig), 6.0));
// Swing-twist: point 3, cone 1, twist 2, spring 3, friction 3.
SOFTSTEP_ANGULAR_KERNEL(SwingTwistJointGroup, swing_twist,
                        3.0 + ((sig & kSwingCone) ? 1 : 0) + ((sig & kTwistLimit) ? 2 : 0) +
                            ((sig & kSwingTwistSpring) ? 3 : 0) +
                            ((sig & kSwingTwistMotor) ? 3 : 0));
// A ragdoll's joint: cone, twist limits and friction (9 rows); and every part (12).
constexpr std::uint32_t kRagdollParts = kSwingCone | kTwistLimit | kSwingTwistMotor;
constexpr std::uint32_t kAllSwingTwistParts = kRagdollParts | kSwingTwistSpring;
SOFTSTEP_ANGULAR_KERNEL(WheelJointGroup, wheel, sig == 0 ? 4.0 : 8.0);
SOFTSTEP_ANGULAR_KERNEL(MotorJointGroup, motor, (void(sig), 6.0));

// F: the kernel variant of ball and distance joints. Every lane of these chains is rigid with
// no limit row, so the general kernel (the default) and the rigid variant compute the same
// thing: their ratio is what specializing saves. Sig: the angular types' parts (0: locks only).
template <class L, template <int> class Group, Stage S, JointFeatures F = kGeneralKernel,
          std::uint32_t Sig = 0>
void run(benchmark::State& state) {
  constexpr int W = kWidth<L>;
  auto p =
      pack_chains<Group, W>(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const BodyArrays arrays = p.bodies.arrays();
  for (auto& color : p.colors) {
    for (auto& g : color)
      Kernel<Group>::template run<L, kGeneralKernel, Stage::Prepare>(g, arrays, Sig);
  }
  for (auto _ : state) {
    for (auto& color : p.colors) {
      for (auto& g : color) Kernel<Group>::template run<L, F, S>(g, arrays, Sig);
    }
    benchmark::ClobberMemory();
  }
  const double rows = static_cast<double>(p.joints) * Kernel<Group>::rows(Sig);
  state.counters["ns_per_row"] = benchmark::Counter(
      rows * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The rigid variant of the ball and distance kernels (no per-lane spring switch, no limit rows).
constexpr JointFeatures kRigid{RowKind::Rigid, false, false};

// (total links, links per chain). Unused where only the contact benchmarks include this.
[[maybe_unused]] void scenes(benchmark::internal::Benchmark* b) {
  b->Args({10000, 10000})
      ->Args({100000, 100000})
      ->Args({100000, 100})
      ->Unit(benchmark::kMicrosecond);
}

}  // namespace
}  // namespace softstep::simd
