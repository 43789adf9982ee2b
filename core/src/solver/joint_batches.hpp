// Joints as the kernels see them: per colour, groups of W lanes (AoSoA), one vector per
// joint type. The overflow set is kept in groups of one lane and runs last, in order.
#pragma once

#include <vector>

#include "softstep/simd/ball_joint_kernel.hpp"
#include "softstep/simd/body_integration.hpp"
#include "softstep/simd/distance_joint_kernel.hpp"

namespace softstep::solver {

template <int W>
struct ColorBatches {
  std::vector<simd::BallJointGroup<W>> ball;
  std::vector<simd::DistanceJointGroup<W>> distance;
};

// This thread's part of the work: thread `thread` of `threads` takes the contiguous slice
// [n * thread / threads, n * (thread + 1) / threads) of any n items. A static split: the
// same thread touches the same groups and bodies in every colour and sub-step (TOOLCHAIN.md:
// records migrating between cores cost more than the barriers).
class StepBarrier;

struct Share {
  int thread = 0;
  int threads = 1;
  double* barrier_wait_us = nullptr;  // when profiling: this thread's time waiting at barriers
  StepBarrier* barrier = nullptr;     // shared by the step's threads when threads > 1
};

struct Slice {
  std::size_t begin, end;
};

// static: every translation unit gets its own copy (see kernel_table.hpp for why).
static inline Slice slice_of(std::size_t n, const Share& s) {
  return {n * static_cast<std::size_t>(s.thread) / static_cast<std::size_t>(s.threads),
          n * static_cast<std::size_t>(s.thread + 1) / static_cast<std::size_t>(s.threads)};
}

// The kernels of one lane width, compiled in a translation unit of their own with that
// width's instruction set (see kernels_*.cpp). Each runs over this thread's share of the
// groups of one colour.
template <int W>
struct KernelTable {
  void (*prepare)(ColorBatches<W>&, const simd::SubstepContext&, const Share&);
  void (*warm_start)(ColorBatches<W>&, const simd::BodyArrays&, const Share&);
  void (*solve)(ColorBatches<W>&, const simd::BodyArrays&, const simd::SubstepContext&,
                const Share&);
  void (*relax)(ColorBatches<W>&, const simd::BodyArrays&, const simd::SubstepContext&,
                const Share&);
  // This thread's share of the bodies [0, count), in blocks of W (count is a multiple of W).
  void (*integrate_velocities)(simd::VelocityRecord*, const simd::ForceRecord*, std::int32_t count,
                               const simd::SubstepContext&, const Share&);
  void (*integrate_positions)(simd::DeltaRecord*, const simd::VelocityRecord*, std::int32_t count,
                              float h, const Share&);
};

KernelTable<1> scalar_kernels();
KernelTable<4> sse_kernels();
KernelTable<8> avx2_kernels();

}  // namespace softstep::solver
