// Builds the kernel table of one lane type. Included only by the kernels_*.cpp files, each
// compiled for its instruction set; nothing else belongs in those files (a shared inline
// function compiled with AVX2 there could be picked by the linker for scalar code).
#pragma once

#include "solver/joint_batches.hpp"

namespace softstep::solver {

// Applies f to this thread's share of the ball groups and then of the distance groups.
template <int W, class Ball, class Distance>
void for_share(ColorBatches<W>& c, const Share& share, Ball&& ball, Distance&& distance) {
  const Slice b = slice_of(c.ball.size(), share);
  for (std::size_t i = b.begin; i < b.end; ++i) ball(c.ball[i]);
  const Slice d = slice_of(c.distance.size(), share);
  for (std::size_t i = d.begin; i < d.end; ++i) distance(c.distance[i]);
}

template <class L>
KernelTable<simd::kWidth<L>> make_kernel_table() {
  constexpr int W = simd::kWidth<L>;
  using Ball = simd::BallJointGroup<W>;
  using Distance = simd::DistanceJointGroup<W>;
  KernelTable<W> t;
  t.prepare = [](ColorBatches<W>& c, const simd::SubstepContext& ctx, const Share& s) {
    for_share(
        c, s, [&](Ball& g) { simd::prepare_ball_joints<L>(g, ctx); },
        [&](Distance& g) { simd::prepare_distance_joints<L>(g, ctx); });
  };
  t.warm_start = [](ColorBatches<W>& c, const simd::BodyArrays& b, const Share& s) {
    for_share(
        c, s, [&](Ball& g) { simd::warm_start_ball_joints<L>(g, b); },
        [&](Distance& g) { simd::warm_start_distance_joints<L>(g, b); });
  };
  t.solve = [](ColorBatches<W>& c, const simd::BodyArrays& b, const simd::SubstepContext& ctx,
               const Share& s) {
    for_share(
        c, s, [&](Ball& g) { simd::solve_ball_joints<L, true>(g, b); },
        [&](Distance& g) { simd::solve_distance_joints<L, true>(g, b, ctx); });
  };
  t.relax = [](ColorBatches<W>& c, const simd::BodyArrays& b, const simd::SubstepContext& ctx,
               const Share& s) {
    for_share(
        c, s, [&](Ball& g) { simd::solve_ball_joints<L, false>(g, b); },
        [&](Distance& g) { simd::solve_distance_joints<L, false>(g, b, ctx); });
  };
  t.integrate_velocities = [](simd::VelocityRecord* v, const simd::ForceRecord* f,
                              std::int32_t count, const simd::SubstepContext& ctx,
                              const Share& s) {
    const Slice blocks = slice_of(static_cast<std::size_t>(count / W), s);
    for (std::size_t i = blocks.begin; i < blocks.end; ++i) {
      simd::integrate_velocities<L>(v, f, static_cast<std::int32_t>(i) * W, ctx);
    }
  };
  t.integrate_positions = [](simd::DeltaRecord* d, const simd::VelocityRecord* v,
                             std::int32_t count, float h, const Share& s) {
    const Slice blocks = slice_of(static_cast<std::size_t>(count / W), s);
    for (std::size_t i = blocks.begin; i < blocks.end; ++i) {
      simd::integrate_positions<L>(d, v, static_cast<std::int32_t>(i) * W, h);
    }
  };
  return t;
}

}  // namespace softstep::solver
