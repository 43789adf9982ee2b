// Builds the body-integration kernels of one lane type. Included only by the kernels_*.cpp
// files, each compiled for its instruction set; nothing else belongs in those files (a shared
// inline function compiled with AVX2 there could be picked by the linker for scalar code).
// The joint kernels are built per kind in the generated files (joints/kind_kernels.cpp.in).
#pragma once

#include "solver/joint_batches.hpp"

namespace softstep::solver {

template <class L, bool kGravity, bool kDamping>
void integrate_velocity_blocks(simd::VelocityRecord* v, const simd::ForceRecord* f,
                               const std::int32_t* blocks, std::size_t count,
                               const simd::SubstepContext& ctx) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int lane = 0; lane < kBodyBlock; lane += simd::kWidth<L>) {
      simd::integrate_velocities<L, kGravity, kDamping>(v, f, blocks[i] + lane, ctx);
    }
  }
}

template <class L>
BodyKernels make_body_kernels() {
  BodyKernels t;
  t.integrate_velocities[0][0] = integrate_velocity_blocks<L, false, false>;
  t.integrate_velocities[0][1] = integrate_velocity_blocks<L, false, true>;
  t.integrate_velocities[1][0] = integrate_velocity_blocks<L, true, false>;
  t.integrate_velocities[1][1] = integrate_velocity_blocks<L, true, true>;
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
