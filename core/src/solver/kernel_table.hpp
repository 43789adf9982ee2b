// Builds the kernel table of one lane type. Included only by the kernels_*.cpp files, each
// compiled for its instruction set; nothing else belongs in those files (a shared inline
// function compiled with AVX2 there could be picked by the linker for scalar code).
#pragma once

#include "solver/joint_batches.hpp"

namespace softstep::solver {

template <class L>
KernelTable<simd::kWidth<L>> make_kernel_table() {
  constexpr int W = simd::kWidth<L>;
  KernelTable<W> t;
  t.prepare = [](ColorBatches<W>& c, const simd::SubstepContext& ctx) {
    for (auto& g : c.ball) simd::prepare_ball_joints<L>(g, ctx);
    for (auto& g : c.distance) simd::prepare_distance_joints<L>(g, ctx);
  };
  t.warm_start = [](ColorBatches<W>& c, const simd::BodyArrays& b) {
    for (auto& g : c.ball) simd::warm_start_ball_joints<L>(g, b);
    for (auto& g : c.distance) simd::warm_start_distance_joints<L>(g, b);
  };
  t.solve = [](ColorBatches<W>& c, const simd::BodyArrays& b, const simd::SubstepContext& ctx) {
    for (auto& g : c.ball) simd::solve_ball_joints<L, true>(g, b);
    for (auto& g : c.distance) simd::solve_distance_joints<L, true>(g, b, ctx);
  };
  t.relax = [](ColorBatches<W>& c, const simd::BodyArrays& b, const simd::SubstepContext& ctx) {
    for (auto& g : c.ball) simd::solve_ball_joints<L, false>(g, b);
    for (auto& g : c.distance) simd::solve_distance_joints<L, false>(g, b, ctx);
  };
  t.integrate_velocities = [](simd::VelocityRecord* v, const simd::ForceRecord* f,
                              std::int32_t count, float h) {
    for (std::int32_t i = 0; i < count; i += W) simd::integrate_velocities<L>(v, f, i, h);
  };
  t.integrate_positions = [](simd::DeltaRecord* d, const simd::VelocityRecord* v,
                             std::int32_t count, float h) {
    for (std::int32_t i = 0; i < count; i += W) simd::integrate_positions<L>(d, v, i, h);
  };
  return t;
}

}  // namespace softstep::solver
