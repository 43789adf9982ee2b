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

template <class L, class Record>
inline Rows8<L> gather_rows(const Record* records, const std::int32_t* index) {
  static_assert(sizeof(Record) == 32);
  Rows8<L> out;
  if constexpr (std::is_same_v<L, float>) {
    const float* p = reinterpret_cast<const float*>(records + index[0]);
    for (int k = 0; k < 8; ++k) out.r[k] = p[k];
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

// Writes `count` leading fields of each lane back, skipping lanes whose mask is false.
template <class L, class Record>
inline void scatter_rows(Record* records, const std::int32_t* index, const Rows8<L>& rows,
                         int count, const MaskOf<L>& write) {
  if constexpr (std::is_same_v<L, float>) {
    if (!write) return;
    float* p = reinterpret_cast<float*>(records + index[0]);
    for (int k = 0; k < count; ++k) p[k] = rows.r[k];
  } else {
    constexpr int W = kWidth<L>;
    alignas(64) float t[8][W];
    for (int k = 0; k < count; ++k) rows.r[k].store_aligned(t[k]);
    alignas(64) float m[W];
    select(write, L(1.0f), L(0.0f)).store_aligned(m);
    for (int i = 0; i < W; ++i) {
      if (m[i] == 0.0f) continue;
      float* p = reinterpret_cast<float*>(records + index[i]);
      for (int k = 0; k < count; ++k) p[k] = t[k][i];
    }
  }
}

template <class L>
struct MassLanes {
  L inv_mass;
  Mat3Sym<L> inv_inertia;
};

template <class L>
inline MassLanes<L> gather_mass(const MassRecord* mass, const std::int32_t* index) {
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

template <class L>
inline BodyLanes<L> gather_body(const VelocityRecord* vel, const DeltaRecord* delta,
                                const MassRecord* mass, const std::int32_t* index) {
  const Rows8<L> a = gather_rows<L>(vel, index);
  const Rows8<L> d = gather_rows<L>(delta, index);
  const MassLanes<L> m = gather_mass<L>(mass, index);
  return {{a.r[0], a.r[1], a.r[2]},
          {a.r[3], a.r[4], a.r[5]},
          {d.r[3], d.r[4], d.r[5], d.r[6]},
          {d.r[0], d.r[1], d.r[2]},
          m.inv_mass,
          m.inv_inertia,
          m.inv_mass > L(0.0f)};
}

template <class L>
inline void scatter_velocity(VelocityRecord* vel, const std::int32_t* index,
                             const BodyLanes<L>& b) {
  Rows8<L> rows{{b.v.x, b.v.y, b.v.z, b.w.x, b.w.y, b.w.z, L(0.0f), L(0.0f)}};
  scatter_rows<L>(vel, index, rows, 6, b.movable);
}

}  // namespace softstep::simd
