// Builds the kernel table of one lane type. Included only by the kernels_*.cpp files, each
// compiled for its instruction set; nothing else belongs in those files (a shared inline
// function compiled with AVX2 there could be picked by the linker for scalar code).
#pragma once

#include <utility>

#include "solver/joint_batches.hpp"

namespace softstep::solver {

// One variant's passes, each a loop over consecutive groups; nullptr for a pass the variant
// does not need.
template <class L, JointFeatures F>
VariantKernels<simd::BallJointGroup<simd::kWidth<L>>> ball_variant() {
  using Group = simd::BallJointGroup<simd::kWidth<L>>;
  VariantKernels<Group> k{};
  k.prepare = [](Group* g, std::size_t n, const simd::SubstepContext& ctx) {
    for (std::size_t i = 0; i < n; ++i) simd::prepare_ball_joints<L, F>(g[i], ctx);
  };
  if constexpr (simd::ball_needs_solve(F)) {
    k.warm_start = [](Group* g, std::size_t n, const simd::BodyArrays& b) {
      for (std::size_t i = 0; i < n; ++i) simd::warm_start_ball_joints<L, F>(g[i], b);
    };
    k.solve = [](Group* g, std::size_t n, const simd::BodyArrays& b, const simd::SubstepContext&) {
      for (std::size_t i = 0; i < n; ++i) simd::solve_ball_joints<L, true, F>(g[i], b);
    };
  }
  if constexpr (simd::ball_needs_relax(F)) {
    k.relax = [](Group* g, std::size_t n, const simd::BodyArrays& b, const simd::SubstepContext&) {
      for (std::size_t i = 0; i < n; ++i) simd::solve_ball_joints<L, false, F>(g[i], b);
    };
  }
  return k;
}

template <class L, JointFeatures F>
VariantKernels<simd::DistanceJointGroup<simd::kWidth<L>>> distance_variant() {
  using Group = simd::DistanceJointGroup<simd::kWidth<L>>;
  VariantKernels<Group> k{};
  k.prepare = [](Group* g, std::size_t n, const simd::SubstepContext& ctx) {
    for (std::size_t i = 0; i < n; ++i) simd::prepare_distance_joints<L, F>(g[i], ctx);
  };
  if constexpr (simd::distance_needs_solve(F)) {
    k.warm_start = [](Group* g, std::size_t n, const simd::BodyArrays& b) {
      for (std::size_t i = 0; i < n; ++i) simd::warm_start_distance_joints<L, F>(g[i], b);
    };
    k.solve = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                 const simd::SubstepContext& ctx) {
      for (std::size_t i = 0; i < n; ++i) simd::solve_distance_joints<L, true, F>(g[i], b, ctx);
    };
  }
  if constexpr (simd::distance_needs_relax(F)) {
    k.relax = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                 const simd::SubstepContext& ctx) {
      for (std::size_t i = 0; i < n; ++i) simd::solve_distance_joints<L, false, F>(g[i], b, ctx);
    };
  }
  return k;
}

template <class L, bool kGravity, bool kDamping, bool kTorque>
void integrate_velocity_blocks(simd::VelocityRecord* v, const simd::ForceRecord* f,
                               const std::int32_t* blocks, std::size_t count,
                               const simd::SubstepContext& ctx) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int lane = 0; lane < kBodyBlock; lane += simd::kWidth<L>) {
      simd::integrate_velocities<L, kGravity, kDamping, kTorque>(v, f, blocks[i] + lane, ctx);
    }
  }
}

template <class L>
KernelTable<simd::kWidth<L>> make_kernel_table() {
  KernelTable<simd::kWidth<L>> t;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    t.ball = {ball_variant<L, kBallVariants[I]>()...};
  }
  (std::make_index_sequence<kBallVariants.size()>());
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    t.distance = {distance_variant<L, kDistanceVariants[I]>()...};
  }
  (std::make_index_sequence<kDistanceVariants.size()>());
  [&]<int... I>(std::integer_sequence<int, I...>) {  // [gravity][damping][torque]
    ((t.integrate_velocities[I >> 2][(I >> 1) & 1][I & 1] =
          integrate_velocity_blocks<L, (I & 4) != 0, (I & 2) != 0, (I & 1) != 0>),
     ...);
  }
  (std::make_integer_sequence<int, 8>());
  t.integrate_positions = [](simd::DeltaRecord* d, const simd::VelocityRecord* v,
                             const std::int32_t* blocks, std::size_t count, float h) {
    for (std::size_t i = 0; i < count; ++i) {
      for (int lane = 0; lane < kBodyBlock; lane += simd::kWidth<L>) {
        simd::integrate_positions<L>(d, v, blocks[i] + lane, h);
      }
    }
  };
  return t;
}

}  // namespace softstep::solver
