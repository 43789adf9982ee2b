// Joints as the kernels see them: per colour, for each kind of the registry, groups of W lanes
// (AoSoA) and the runs that cut them by kernel variant and signature. The overflow set is kept
// in groups of one lane and runs last, in order.
#pragma once

#include <tuple>
#include <vector>

#include "joints/joint_registry.hpp"
#include "paged_vector.hpp"
#include "softstep/simd/body_integration.hpp"

namespace softstep::solver {

// Consecutive groups [begin, end) of one colour, one kernel variant (an index into the kind's
// variants) and one signature (the parts its joints have).
struct Run {
  std::uint8_t variant;
  std::uint32_t signature;
  std::uint32_t begin, end;
};

template <class Kind, int W>
struct KindBatches {
  using Group = typename Kind::template Group<W>;
  // The kernels load every field with aligned loads of W floats (64 bytes at 16 lanes).
  static_assert(alignof(Group) >= sizeof(float) * W,
                "declare the kind's lane group alignas(simd::kLaneAlign<W>)");
  PagedVector<Group> groups;
  std::vector<Run> runs;
};

template <int W>
struct BatchesOf {
  template <class Kind>
  using Of = KindBatches<Kind, W>;
};
template <int W>
using ColorBatches = JointKinds::Apply<BatchesOf<W>::template Of>;

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

// static: every translation unit gets its own copy (see kind_kernels.hpp for why).
static inline Slice slice_of(std::size_t n, const Share& s) {
  return {n * static_cast<std::size_t>(s.thread) / static_cast<std::size_t>(s.threads),
          n * static_cast<std::size_t>(s.thread + 1) / static_cast<std::size_t>(s.threads)};
}

// Body integration over blocks of 8 records (each entry of `blocks` is a block's first
// record), one function per combination of forces present: [gravity][damping][torque].
using IntegrateVelocities = void (*)(simd::VelocityRecord*, const simd::ForceRecord*,
                                     const std::int32_t* blocks, std::size_t count,
                                     const simd::SubstepContext&);
using IntegratePositions = void (*)(simd::DeltaRecord*, simd::VelocityRecord*,
                                    const std::int32_t* blocks, std::size_t count,
                                    const simd::SubstepContext&);
inline constexpr int kBodyBlock = 8;

struct BodyKernels {
  IntegrateVelocities integrate_velocities[2][2][2];
  IntegratePositions integrate_positions;
  // The same over single records (each entry one body's record, one lane wide: the same bits
  // as in a block), for bodies that do not fill blocks: a tree island's, stepped on its own.
  IntegrateVelocities integrate_velocity_records[2][2][2];
  IntegratePositions integrate_position_records;
};

template <int W>
struct KernelsOf {
  template <class Kind>
  using Of = KindKernels<Kind, W>;
};

// The kernels of one lane width: every kind's (compiled in its own translation units) and the
// body integration (kernels_<width>.cpp).
template <int W>
struct KernelTable {
  JointKinds::Apply<KernelsOf<W>::template Of> joints;
  BodyKernels bodies;
};

BodyKernels scalar_body_kernels();
BodyKernels sse_body_kernels();
BodyKernels avx2_body_kernels();

// Every kind's kernels at width W and the body kernels.
template <int W>
KernelTable<W> kernel_table(BodyKernels bodies) {
  KernelTable<W> t;
  JointKinds::for_each([&]<class Kind>() {
    std::get<JointKinds::index_of<Kind>()>(t.joints) = kind_kernels<Kind, W>();
  });
  t.bodies = bodies;
  return t;
}

}  // namespace softstep::solver
