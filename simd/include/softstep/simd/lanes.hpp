// Lane types: the scalar lane `float` and xsimd batches share one small vocabulary, so a
// kernel written once as a template over L runs at any width with the same arithmetic.
//
// Why our own overloads and not xsimd's: xsimd 8.1 lacks several of these for plain float
// (select(bool,..), fnma), and its rsqrt/reciprocal are approximations that would make the
// widths disagree. Every operation here is correctly rounded in every width, and fusion is
// decided once for the whole build (SOFTSTEP_USE_FMA), so scalar and wide results agree bit
// for bit.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <xsimd/xsimd.hpp>
#if SOFTSTEP_USE_FMA
#include <immintrin.h>
#endif

#ifndef SOFTSTEP_USE_FMA
#define SOFTSTEP_USE_FMA 0
#endif

// Kernels are built from many small helpers over batch types; when gcc declines to inline
// one (it did for the 8-wide gather and transpose), its batches go through memory and the
// AVX2 kernel ran slower than SSE. Every helper here is forced inline.
// Except under AddressSanitizer, where speed does not matter: forced into each of the
// kernel variants (joint_batches.hpp) with every access instrumented, one kernel table took
// over 10 minutes to compile (5x the general kernels alone). There the compiler chooses; the
// arithmetic, and so every result, is the same inlined or not (contraction is off).
#if defined(__SANITIZE_ADDRESS__)
#define SOFTSTEP_INLINE inline
#else
#define SOFTSTEP_INLINE inline __attribute__((always_inline))
#endif

namespace softstep::simd {

template <class L>
struct LaneTraits;

template <>
struct LaneTraits<float> {
  static constexpr int width = 1;
  using Mask = bool;
};

template <class Arch>
struct LaneTraits<xsimd::batch<float, Arch>> {
  static constexpr int width = static_cast<int>(xsimd::batch<float, Arch>::size);
  using Mask = xsimd::batch_bool<float, Arch>;
};

template <class L>
inline constexpr int kWidth = LaneTraits<L>::width;

template <class L>
using MaskOf = typename LaneTraits<L>::Mask;

// The alignment of a lane group of W lanes: every field is an array of W 4-byte values loaded
// with aligned loads, so a 16-lane group needs 64 bytes (a whole AVX-512 register); narrower
// groups keep the 32 bytes they always had, so their layout does not change.
template <int W>
inline constexpr std::size_t kLaneAlign = W * 4 > 32 ? static_cast<std::size_t>(W) * 4 : 32;

// ---- scalar lane -------------------------------------------------------------------------

SOFTSTEP_INLINE void store_lanes(float* p, float v) {
  *p = v;
}
SOFTSTEP_INLINE float fmadd(float a, float b, float c) {
#if SOFTSTEP_USE_FMA
  return std::fma(a, b, c);
#else
  return a * b + c;
#endif
}
SOFTSTEP_INLINE float select(bool m, float a, float b) {
  return m ? a : b;
}
SOFTSTEP_INLINE float min_lanes(float a, float b) {
  return a < b ? a : b;
}
SOFTSTEP_INLINE float max_lanes(float a, float b) {
  return a > b ? a : b;
}
SOFTSTEP_INLINE float sqrt_lanes(float a) {
  return std::sqrt(a);
}

// ---- batch lanes -------------------------------------------------------------------------

template <class A>
SOFTSTEP_INLINE void store_lanes(float* p, const xsimd::batch<float, A>& v) {
  v.store_aligned(p);
}
// With SOFTSTEP_USE_FMA the fused instruction is called directly: xsimd 8.1 offers 4-wide
// FMA only as fma3<sse4_2>, which it disables whenever AVX is on (and gcc's -mfma implies
// AVX), and its plain avx2 arch splits fma into a multiply and an add.
template <class A>
SOFTSTEP_INLINE xsimd::batch<float, A> fmadd(const xsimd::batch<float, A>& a,
                                             const xsimd::batch<float, A>& b,
                                             const xsimd::batch<float, A>& c) {
#if SOFTSTEP_USE_FMA
  if constexpr (xsimd::batch<float, A>::size == 16) {
#if defined(__AVX512F__)
    return _mm512_fmadd_ps(a, b, c);
#endif
  } else if constexpr (xsimd::batch<float, A>::size == 8) {
    return _mm256_fmadd_ps(a, b, c);
  } else {
    static_assert(xsimd::batch<float, A>::size == 4);
    return _mm_fmadd_ps(a, b, c);
  }
#else
  return a * b + c;
#endif
}
template <class A>
SOFTSTEP_INLINE xsimd::batch<float, A> select(const xsimd::batch_bool<float, A>& m,
                                              const xsimd::batch<float, A>& a,
                                              const xsimd::batch<float, A>& b) {
  return xsimd::select(m, a, b);
}
// min/max are written as selects so that the NaN and signed-zero behaviour is exactly the
// scalar `a < b ? a : b` in every width (minps and std::min differ on NaN operands).
template <class A>
SOFTSTEP_INLINE xsimd::batch<float, A> min_lanes(const xsimd::batch<float, A>& a,
                                                 const xsimd::batch<float, A>& b) {
  return xsimd::select(a < b, a, b);
}
template <class A>
SOFTSTEP_INLINE xsimd::batch<float, A> max_lanes(const xsimd::batch<float, A>& a,
                                                 const xsimd::batch<float, A>& b) {
  return xsimd::select(a > b, a, b);
}
template <class A>
SOFTSTEP_INLINE xsimd::batch<float, A> sqrt_lanes(const xsimd::batch<float, A>& a) {
  return xsimd::sqrt(a);
}

// Whether some lane of a comparison holds: lets a kernel skip work that no lane needs.
SOFTSTEP_INLINE bool any_lane(bool m) {
  return m;
}
template <class A>
SOFTSTEP_INLINE bool any_lane(const xsimd::batch_bool<float, A>& m) {
  return xsimd::any(m);
}

// Generic load: `load<L>(p)` reads kWidth<L> consecutive, aligned floats.
template <class L>
SOFTSTEP_INLINE L load(const float* p) {
  if constexpr (std::is_same_v<L, float>) {
    return *p;
  } else {
    return L::load_aligned(p);
  }
}

}  // namespace softstep::simd
