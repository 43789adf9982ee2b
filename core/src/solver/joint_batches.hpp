// Joints as the kernels see them: per colour, groups of W lanes (AoSoA), one vector per
// joint type. The overflow set is kept in groups of one lane and runs last, in order.
#pragma once

#include <array>
#include <vector>

#include "softstep/simd/ball_joint_kernel.hpp"
#include "softstep/simd/body_integration.hpp"
#include "softstep/simd/distance_joint_kernel.hpp"

namespace softstep::solver {

using simd::JointFeatures;
using simd::RowKind;

// The kernel variants the solver is built with, per constraint type: entry 0 is the general
// kernel (every feature, switched per lane), the others are exact signatures. A joint's
// signature depends only on its definition, so it never changes while the joint lives.
inline constexpr std::array kBallVariants{
    simd::kGeneralKernel,
    JointFeatures{RowKind::Rigid, false, false},
    JointFeatures{RowKind::Soft, false, false},
    JointFeatures{RowKind::Free, false, false},
};
inline constexpr std::array kDistanceVariants{
    simd::kGeneralKernel,
    JointFeatures{RowKind::Rigid, false, false},  // a rod has no limit rows
    JointFeatures{RowKind::Soft, false, false},
    JointFeatures{RowKind::Soft, true, false},
    JointFeatures{RowKind::Soft, false, true},
    JointFeatures{RowKind::Soft, true, true},
    JointFeatures{RowKind::Free, false, false},
    JointFeatures{RowKind::Free, true, false},
    JointFeatures{RowKind::Free, false, true},
    JointFeatures{RowKind::Free, true, true},
};

// Consecutive groups [begin, end) of one colour and one kernel variant (an index into
// kBallVariants or kDistanceVariants).
struct Run {
  std::uint8_t variant;
  std::uint32_t begin, end;
};

template <int W>
struct ColorBatches {
  std::vector<simd::BallJointGroup<W>> ball;
  std::vector<Run> ball_runs;
  std::vector<simd::DistanceJointGroup<W>> distance;
  std::vector<Run> distance_runs;
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

// The kernels of one variant of one constraint type over `count` consecutive groups.
// A pass the variant does not need is nullptr (the plan does not schedule it).
template <class Group>
struct VariantKernels {
  void (*prepare)(Group*, std::size_t count, const simd::SubstepContext&);
  void (*warm_start)(Group*, std::size_t count, const simd::BodyArrays&);
  void (*solve)(Group*, std::size_t count, const simd::BodyArrays&, const simd::SubstepContext&);
  void (*relax)(Group*, std::size_t count, const simd::BodyArrays&, const simd::SubstepContext&);
};

// Body integration over blocks of 8 records (each entry of `blocks` is a block's first
// record), one function per combination of forces present: [gravity][damping][torque].
using IntegrateVelocities = void (*)(simd::VelocityRecord*, const simd::ForceRecord*,
                                     const std::int32_t* blocks, std::size_t count,
                                     const simd::SubstepContext&);
using IntegratePositions = void (*)(simd::DeltaRecord*, const simd::VelocityRecord*,
                                    const std::int32_t* blocks, std::size_t count, float h);
inline constexpr int kBodyBlock = 8;

// The kernels of one lane width, compiled in a translation unit of their own with that
// width's instruction set (see kernels_*.cpp).
template <int W>
struct KernelTable {
  std::array<VariantKernels<simd::BallJointGroup<W>>, kBallVariants.size()> ball;
  std::array<VariantKernels<simd::DistanceJointGroup<W>>, kDistanceVariants.size()> distance;
  IntegrateVelocities integrate_velocities[2][2][2];
  IntegratePositions integrate_positions;
};

KernelTable<1> scalar_kernels();
KernelTable<4> sse_kernels();
KernelTable<8> avx2_kernels();

}  // namespace softstep::solver
