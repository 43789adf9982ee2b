// Solver body state: three arrays of 32-byte records, split by how often they are touched.
//
// Why records and not one array per component: in cache, loading W whole 32-byte records
// and transposing them beats W x 8 scalar gathers by 2-3x, and out of cache one record is
// one cache-line access instead of eight (TOOLCHAIN.md, "Where the time goes"). Why three
// arrays: the velocity record is read and written by every iteration, the delta record
// only read by iterations (written once per sub-step), the mass record is constant over
// a step; keeping them apart halves the bytes written per iteration.
//
// Index 0 of every array is the static dummy body: zero velocity, identity rotation delta,
// zero inverse mass. Static bodies and padding lanes point at it, so kernels never branch
// on "is this lane real". A body whose inverse mass is zero (static, kinematic, dummy) is
// never written back: constraints of one colour may share such a body.
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <cstring>

#include "softstep/simd/math3.hpp"

namespace softstep::simd {

struct alignas(32) VelocityRecord {
  float v[3];  // linear velocity of the centre of mass, m/s
  float w[3];  // angular velocity, rad/s (world frame)
  float unused[2];
};

struct alignas(32) DeltaRecord {
  float dp[3];  // displacement of the centre of mass since the start of the step, m
  float dq[4];  // rotation since the start of the step (x, y, z, w)
  float unused;
};

struct alignas(32) MassRecord {
  float inv_mass;        // 1/kg; 0 for static, kinematic and the dummy
  float inv_inertia[6];  // world-frame inverse inertia at the start of the step: xx yy zz xy xz yz
  float unused;
};

static_assert(sizeof(VelocityRecord) == 32 && sizeof(DeltaRecord) == 32 &&
              sizeof(MassRecord) == 32);

inline constexpr std::int32_t kDummyBody = 0;

// Eight floats of W records, transposed so that row k holds field k of every lane.
template <class L>
struct Rows8 {
  L r[8];
};

namespace detail {

#if defined(__AVX__)
// In-register transpose of eight 8-float rows: afterwards row k holds element k of each.
SOFTSTEP_INLINE void transpose8(__m256 (&r)[8]) {
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
  const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 u1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 u3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 u4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 u5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 u6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 u7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
  r[0] = _mm256_permute2f128_ps(u0, u4, 0x20);
  r[1] = _mm256_permute2f128_ps(u1, u5, 0x20);
  r[2] = _mm256_permute2f128_ps(u2, u6, 0x20);
  r[3] = _mm256_permute2f128_ps(u3, u7, 0x20);
  r[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
  r[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
  r[6] = _mm256_permute2f128_ps(u2, u6, 0x31);
  r[7] = _mm256_permute2f128_ps(u3, u7, 0x31);
}
#endif

#if defined(__AVX512F__)
// Sixteen records as two eight-record halves, each transposed like AVX2 does, then joined:
// row k holds field k of records 0-7 in its low and of records 8-15 in its high 256 bits.
SOFTSTEP_INLINE __m512 join_halves(__m256 lo, __m256 hi) {
  return _mm512_castpd_ps(
      _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}
SOFTSTEP_INLINE __m256 low_half(__m512 r) {
  return _mm512_castps512_ps256(r);
}
// A shuffle rather than _mm512_extractf64x4_pd: gcc 12's -Wuninitialized flags the undefined
// pass-through operand of the extract intrinsic.
SOFTSTEP_INLINE __m256 high_half(__m512 r) {
  return _mm512_castps512_ps256(_mm512_shuffle_f32x4(r, r, _MM_SHUFFLE(3, 2, 3, 2)));
}
#endif

template <class L>
inline constexpr bool kIsAvx512Batch = false;
#if defined(__AVX512F__)
template <class A>
inline constexpr bool kIsAvx512Batch<xsimd::batch<float, A>> = xsimd::batch<float, A>::size == 16;
#endif
template <class L>
inline constexpr bool kIsAvxBatch = false;
template <class L>
inline constexpr bool kIsSseBatch = false;
#if defined(__AVX__)
template <class A>
inline constexpr bool kIsAvxBatch<xsimd::batch<float, A>> = xsimd::batch<float, A>::size == 8;
#endif
#if defined(__SSE2__)
template <class A>
inline constexpr bool kIsSseBatch<xsimd::batch<float, A>> = xsimd::batch<float, A>::size == 4;
#endif

}  // namespace detail

// Loads field k of record index[i] into lane i of row k. Whole records are loaded and
// transposed in registers (TOOLCHAIN.md: 2-3x faster than per-lane gathers in cache).
template <class L, class Record>
SOFTSTEP_INLINE Rows8<L> gather_rows(const Record* records, const std::int32_t* index) {
  static_assert(sizeof(Record) == 32 && alignof(Record) == 32);
  Rows8<L> out;
  if constexpr (std::is_same_v<L, float>) {
    const float* p = reinterpret_cast<const float*>(records + index[0]);
    for (int k = 0; k < 8; ++k) out.r[k] = p[k];
#if defined(__AVX512F__)
  } else if constexpr (detail::kIsAvx512Batch<L>) {
    __m256 lo[8], hi[8];
    for (int i = 0; i < 8; ++i) {
      lo[i] = _mm256_load_ps(reinterpret_cast<const float*>(records + index[i]));
      hi[i] = _mm256_load_ps(reinterpret_cast<const float*>(records + index[i + 8]));
    }
    detail::transpose8(lo);
    detail::transpose8(hi);
    for (int k = 0; k < 8; ++k) out.r[k] = L(detail::join_halves(lo[k], hi[k]));
#endif
#if defined(__AVX__)
  } else if constexpr (detail::kIsAvxBatch<L>) {
    __m256 r[8];
    for (int i = 0; i < 8; ++i)
      r[i] = _mm256_load_ps(reinterpret_cast<const float*>(records + index[i]));
    detail::transpose8(r);
    for (int k = 0; k < 8; ++k) out.r[k] = L(r[k]);
#endif
  } else if constexpr (detail::kIsSseBatch<L>) {
    __m128 lo[4], hi[4];
    for (int i = 0; i < 4; ++i) {
      const float* p = reinterpret_cast<const float*>(records + index[i]);
      lo[i] = _mm_load_ps(p);
      hi[i] = _mm_load_ps(p + 4);
    }
    _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
    _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
    for (int k = 0; k < 4; ++k) {
      out.r[k] = L(lo[k]);
      out.r[k + 4] = L(hi[k]);
    }
  } else {
    constexpr int W = kWidth<L>;
    alignas(64) float t[8][W];
    for (int i = 0; i < W; ++i) {
      const float* p = reinterpret_cast<const float*>(records + index[i]);
      for (int k = 0; k < 8; ++k) t[k][i] = p[k];
    }
    for (int k = 0; k < 8; ++k) out.r[k] = L::load_aligned(t[k]);
  }
  return out;
}

// Writes the rows back as whole records, only for lanes whose mask is set (a body that cannot
// move is shared by lanes of one colour and must not be written). Fields a record does not
// use are written with whatever the rows hold there.
template <class L, class Record>
SOFTSTEP_INLINE void scatter_rows(Record* records, const std::int32_t* index, const Rows8<L>& rows,
                                  const MaskOf<L>& write) {
  if constexpr (std::is_same_v<L, float>) {
    if (!write) return;
    float* p = reinterpret_cast<float*>(records + index[0]);
    for (int k = 0; k < 8; ++k) p[k] = rows.r[k];
#if defined(__AVX512F__)
  } else if constexpr (detail::kIsAvx512Batch<L>) {
    __m256 r[2][8];
    for (int k = 0; k < 8; ++k) {
      r[0][k] = detail::low_half(rows.r[k]);
      r[1][k] = detail::high_half(rows.r[k]);
    }
    detail::transpose8(r[0]);
    detail::transpose8(r[1]);
    unsigned mask = static_cast<unsigned>(static_cast<__mmask16>(write.data));
    while (mask != 0) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      _mm256_store_ps(reinterpret_cast<float*>(records + index[i]), r[i >> 3][i & 7]);
    }
#endif
#if defined(__AVX__)
  } else if constexpr (detail::kIsAvxBatch<L>) {
    __m256 r[8];
    for (int k = 0; k < 8; ++k) r[k] = rows.r[k];
    detail::transpose8(r);
    unsigned mask = static_cast<unsigned>(_mm256_movemask_ps(write));
    while (mask != 0) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      _mm256_store_ps(reinterpret_cast<float*>(records + index[i]), r[i]);
    }
#endif
  } else if constexpr (detail::kIsSseBatch<L>) {
    __m128 lo[4], hi[4];
    for (int k = 0; k < 4; ++k) {
      lo[k] = rows.r[k];
      hi[k] = rows.r[k + 4];
    }
    _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
    _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
    unsigned mask = static_cast<unsigned>(_mm_movemask_ps(write));
    while (mask != 0) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      float* p = reinterpret_cast<float*>(records + index[i]);
      _mm_store_ps(p, lo[i]);
      _mm_store_ps(p + 4, hi[i]);
    }
  } else {
    constexpr int W = kWidth<L>;
    alignas(64) float t[8][W];
    for (int k = 0; k < 8; ++k) rows.r[k].store_aligned(t[k]);
    alignas(64) float m[W];
    select(write, L(1.0f), L(0.0f)).store_aligned(m);
    for (int i = 0; i < W; ++i) {
      if (m[i] == 0.0f) continue;
      float* p = reinterpret_cast<float*>(records + index[i]);
      for (int k = 0; k < 8; ++k) p[k] = t[k][i];
    }
  }
}

template <class L>
struct MassLanes {
  L inv_mass;
  Mat3Sym<L> inv_inertia;
};

template <class L>
SOFTSTEP_INLINE MassLanes<L> gather_mass(const MassRecord* mass, const std::int32_t* index) {
  const Rows8<L> m = gather_rows<L>(mass, index);
  return {m.r[0], {m.r[1], m.r[2], m.r[3], m.r[4], m.r[5], m.r[6]}};
}

// Body state of one side (A or B) of W constraints, as the kernels use it.
template <class L>
struct BodyLanes {
  Vec3<L> v, w;
  Quat<L> dq;
  Vec3<L> dp;
  L inv_mass;
  Mat3Sym<L> inv_inertia;
  MaskOf<L> movable;  // inverse mass > 0: only these lanes are written back
};

// Fills `out` field by field from the transposed rows. Built by value and then copied into a
// kernel's JointBodies (which the compiler keeps in memory: a kernel has more live batches
// than registers), a BodyLanes went through a block copy of its 21 batches per body (rep movs),
// and a zero-filled JointBodies through a memset of all 51: most of the fixed cost of a cheap
// kernel at 8 lanes (the wheel's locks).
// The velocity records' part of a BodyLanes (gather_body_into; the contacts gather it alone).
template <class L>
SOFTSTEP_INLINE void gather_velocity_into(BodyLanes<L>& out, const VelocityRecord* vel,
                                          const std::int32_t* index) {
  const Rows8<L> a = gather_rows<L>(vel, index);
  out.v = {a.r[0], a.r[1], a.r[2]};
  out.w = {a.r[3], a.r[4], a.r[5]};
}

// The delta records' part of a BodyLanes.
template <class L>
SOFTSTEP_INLINE void gather_delta_into(BodyLanes<L>& out, const DeltaRecord* delta,
                                       const std::int32_t* index) {
  const Rows8<L> d = gather_rows<L>(delta, index);
  out.dq = {d.r[3], d.r[4], d.r[5], d.r[6]};
  out.dp = {d.r[0], d.r[1], d.r[2]};
}

template <class L>
SOFTSTEP_INLINE void gather_body_into(BodyLanes<L>& out, const VelocityRecord* vel,
                                      const DeltaRecord* delta, const MassRecord* mass,
                                      const std::int32_t* index) {
  gather_velocity_into(out, vel, index);
  gather_delta_into(out, delta, index);
  const MassLanes<L> m = gather_mass<L>(mass, index);
  out.inv_mass = m.inv_mass;
  out.inv_inertia = m.inv_inertia;
  out.movable = m.inv_mass > L(0.0f);
}

template <class L>
SOFTSTEP_INLINE BodyLanes<L> gather_body(const VelocityRecord* vel, const DeltaRecord* delta,
                                         const MassRecord* mass, const std::int32_t* index) {
  BodyLanes<L> b;
  gather_body_into(b, vel, delta, mass, index);
  return b;
}

template <class L>
SOFTSTEP_INLINE void scatter_velocity(VelocityRecord* vel, const std::int32_t* index,
                                      const BodyLanes<L>& b) {
#if defined(__AVX__)
  if constexpr (detail::kIsAvxBatch<L>) {
    // The rows straight into registers: a Rows8 aggregate of batches copied from a body kept
    // in memory was copied in 8-byte pieces, and reading it back as whole rows stalled on
    // store forwarding.
    __m256 r[8] = {b.v.x, b.v.y, b.v.z, b.w.x, b.w.y, b.w.z, _mm256_setzero_ps(),
                   _mm256_setzero_ps()};
    detail::transpose8(r);
    unsigned mask = static_cast<unsigned>(_mm256_movemask_ps(b.movable));
    while (mask != 0) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      _mm256_store_ps(reinterpret_cast<float*>(vel + index[i]), r[i]);
    }
    return;
  }
#endif
  const Rows8<L> rows{{b.v.x, b.v.y, b.v.z, b.w.x, b.w.y, b.w.z, L(0.0f), L(0.0f)}};
  scatter_rows<L>(vel, index, rows, b.movable);
}

}  // namespace softstep::simd
