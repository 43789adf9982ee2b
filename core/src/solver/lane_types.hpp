// The lane type of each width. Included only by translation units compiled for that width's
// instruction set (the kernel tables).
#pragma once

#include <xsimd/xsimd.hpp>

namespace softstep::solver {
using ScalarLane = float;
#if defined(__SSE4_2__)
using SseLane = xsimd::batch<float, xsimd::sse4_2>;
#endif
#if defined(__AVX2__)
using Avx2Lane = xsimd::batch<float, xsimd::avx2>;
#endif
#if defined(__AVX512BW__)
using Avx512Lane = xsimd::batch<float, xsimd::avx512bw>;
#endif
}  // namespace softstep::solver
