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

// The kernels of one lane width, compiled in a translation unit of their own with that
// width's instruction set (see kernels_*.cpp). Each runs over every group of one colour.
template <int W>
struct KernelTable {
  void (*prepare)(ColorBatches<W>&, const simd::SubstepContext&);
  void (*warm_start)(ColorBatches<W>&, const simd::BodyArrays&);
  void (*solve)(ColorBatches<W>&, const simd::BodyArrays&, const simd::SubstepContext&);
  void (*relax)(ColorBatches<W>&, const simd::BodyArrays&, const simd::SubstepContext&);
  // Bodies [0, count): count is a multiple of W (the record arrays are padded).
  void (*integrate_velocities)(simd::VelocityRecord*, const simd::ForceRecord*, std::int32_t count,
                               float h);
  void (*integrate_positions)(simd::DeltaRecord*, const simd::VelocityRecord*, std::int32_t count,
                              float h);
};

KernelTable<1> scalar_kernels();
KernelTable<4> sse_kernels();
KernelTable<8> avx2_kernels();

}  // namespace softstep::solver
