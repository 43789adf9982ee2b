// The contact kernels of one lane width as a table of functions, one per pass and signature
// (simd/contact_kernel.hpp): the solver, compiled without any instruction-set flags, calls
// through it; contact_kernels_<width>.cpp build it, each compiled for its instruction set.
#pragma once

#include <array>
#include <cstddef>

#include "softstep/simd/contact_kernel.hpp"

namespace softstep::solver {

template <int W>
struct ContactKernels {
  using Group = simd::ContactLanes<W>;
  using Pass = void (*)(Group*, std::size_t count, const simd::BodyArrays&,
                        const simd::SubstepContext&, const simd::ContactContext&);
  std::array<Pass, simd::kContactSignatures> prepare{}, warm_start{}, solve{}, relax{};
  Pass restitute = nullptr;
};

ContactKernels<1> scalar_contact_kernels();
ContactKernels<4> sse_contact_kernels();
ContactKernels<8> avx2_contact_kernels();
ContactKernels<16> avx512_contact_kernels();

}  // namespace softstep::solver
