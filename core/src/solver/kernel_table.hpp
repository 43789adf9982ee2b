// Builds the body-integration kernels of one lane type. Included only by the kernels_*.cpp
// files, each compiled for its instruction set; nothing else belongs in those files (a shared
// inline function compiled with AVX2 there could be picked by the linker for scalar code).
// The joint kernels are built per kind in the generated files (joints/kind_kernels.cpp.in).
#pragma once

#include <utility>

#include "solver/joint_batches.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {

// Each entry of `blocks` is the first of kBlock records (kBodyBlock, or 1 for single records).
template <class L, int kBlock, bool kGravity, bool kDamping, bool kTorque>
void integrate_velocity_blocks(simd::VelocityRecord* v, const simd::ForceRecord* f,
                               const std::int32_t* blocks, std::size_t count,
                               const simd::SubstepContext& ctx) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int lane = 0; lane < kBlock; lane += simd::kWidth<L>) {
      simd::integrate_velocities<L, kGravity, kDamping, kTorque>(v, f, blocks[i] + lane, ctx);
    }
  }
}

template <class L, int kBlock>
void integrate_position_blocks(simd::DeltaRecord* d, simd::VelocityRecord* v,
                               const std::int32_t* blocks, std::size_t count,
                               const simd::SubstepContext& ctx) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int lane = 0; lane < kBlock; lane += simd::kWidth<L>) {
      simd::integrate_positions<L>(d, v, blocks[i] + lane, ctx);
    }
  }
}

template <class L>
BodyKernels make_body_kernels() {
  BodyKernels t;
  [&]<int... I>(std::integer_sequence<int, I...>) {  // [gravity][damping][torque]
    ((t.integrate_velocities[I >> 2][(I >> 1) & 1][I & 1] =
          integrate_velocity_blocks<L, kBodyBlock, (I & 4) != 0, (I & 2) != 0, (I & 1) != 0>),
     ...);
    ((t.integrate_velocity_records[I >> 2][(I >> 1) & 1][I & 1] =
          integrate_velocity_blocks<ScalarLane, 1, (I & 4) != 0, (I & 2) != 0, (I & 1) != 0>),
     ...);
  }(std::make_integer_sequence<int, 8>());
  t.integrate_positions = integrate_position_blocks<L, kBodyBlock>;
  t.integrate_position_records = integrate_position_blocks<ScalarLane, 1>;
  return t;
}

}  // namespace softstep::solver
