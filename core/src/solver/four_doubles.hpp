// Four doubles in one 256-bit GCC vector (two SSE registers in a build without AVX), for the
// small double-precision arithmetic outside the kernels' lanes: the rows of a tree joint's 3x3
// and 3x6 blocks (three doubles and a zero), a contact manifold's four points, and the anchors
// of four joints of a lane group. Each element
// takes the operations written, in that order: with -ffp-contract=off (project-wide) a vector
// expression gives the bits its scalar spelling would.
#pragma once

// Passing or returning a 32-byte vector without AVX changes the calling convention, and gcc
// and clang warn (-Wpsabi) wherever one crosses a function boundary. Every function that takes
// or returns one has internal linkage (an anonymous namespace or inline in this header), so no
// two object files call each other with different conventions; the warning is off in the
// files that include this one.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <Eigen/Core>
#include <cmath>
#if SOFTSTEP_USE_FMA
#include <immintrin.h>
#endif

namespace softstep {

using FourDoubles = double __attribute__((vector_size(32)));

// a * b + c in one rounding where the build fuses multiply-adds (SOFTSTEP_USE_FMA, as the
// kernels do: simd/lanes.hpp), else in two. Only the exact tree solve uses these (its bits
// are its own, the same at every width and thread count in a build); the lanes that must
// give Eigen's bits (lane_solver.cpp, contact_solver.cpp) keep the plain operators. A fused
// product is one instruction where the unfused one is two, and one latency where its
// dependent chains (a link's 3x3 inverse, a solve's pass along a chain) had two.
[[gnu::always_inline]] inline double multiply_add(double a, double b, double c) {
#if SOFTSTEP_USE_FMA
  return std::fma(a, b, c);
#else
  return a * b + c;
#endif
}

[[gnu::always_inline]] inline FourDoubles multiply_add(const FourDoubles& a, const FourDoubles& b,
                                                       const FourDoubles& c) {
#if SOFTSTEP_USE_FMA
  return _mm256_fmadd_pd(a, b, c);
#else
  return a * b + c;
#endif
}

// a broadcast to every element.
[[gnu::always_inline]] inline FourDoubles multiply_add(double a, const FourDoubles& b,
                                                       const FourDoubles& c) {
  return multiply_add(FourDoubles{a, a, a, a}, b, c);
}

// p[0..2] and a zero.
[[gnu::always_inline]] inline FourDoubles load3(const double* p) {
  return FourDoubles{p[0], p[1], p[2], 0.0};
}

[[gnu::always_inline]] inline void store3(double* p, const FourDoubles& r) {
  p[0] = r[0];
  p[1] = r[1];
  p[2] = r[2];
}

// v[0..3], one element per lane.
[[gnu::always_inline]] inline FourDoubles load4(const double (&v)[4]) {
  return FourDoubles{v[0], v[1], v[2], v[3]};
}

// M v for a column-major 3x6 M: its columns scaled by v and summed in column order (fused,
// multiply_add).
[[gnu::always_inline]] inline FourDoubles times_vector(const Eigen::Matrix<double, 3, 6>& m,
                                                       const Eigen::Matrix<double, 6, 1>& v) {
  const double* c = m.data();
  FourDoubles sum = load3(c) * v[0];
  for (int k = 1; k < 6; ++k) sum = multiply_add(v[k], load3(c + 3 * k), sum);
  return sum;
}

[[gnu::always_inline]] inline void store4(double (&p)[4], const FourDoubles& v) {
  __builtin_memcpy(p, &v, sizeof(v));
}

// v's elements turned: (y, z, x) and (z, x, y) (the fourth stays).
[[gnu::always_inline]] inline FourDoubles yzx(const FourDoubles& v) {
  return __builtin_shufflevector(v, v, 1, 2, 0, 3);
}
[[gnu::always_inline]] inline FourDoubles zxy(const FourDoubles& v) {
  return __builtin_shufflevector(v, v, 2, 0, 1, 3);
}

// a x b, each element's product of b's turned elements rounded first (fused, multiply_add).
[[gnu::always_inline]] inline FourDoubles cross(const FourDoubles& a, const FourDoubles& b) {
  return multiply_add(yzx(a), zxy(b), -(zxy(a) * yzx(b)));
}

// Three vectors' x, y and z, one vector per lane.
struct FourVectors {
  FourDoubles x, y, z;
};

// Lane arrays of x, y and z (v[axis][lane]) as vectors. Gathering a lane's fields into plain
// arrays and making the vectors here keeps the vectors in registers: zero-filled vectors filled
// in place cost rep stos per use (perf), and a lambda returning a vector may be emitted out of
// line without AVX, where gcc rejects the changed return ABI (-Wpsabi, an error here).
[[gnu::always_inline]] inline FourVectors load_vectors(const double (&v)[3][4]) {
  return {load4(v[0]), load4(v[1]), load4(v[2])};
}

// q v in every lane, as Eigen's Quaternion::_transformVector: uv = 2 (q.vec x v), then
// v + w uv + q.vec x uv. Q is double (one quaternion turns every lane's vector: a contact
// manifold's points) or FourDoubles (a quaternion per lane: four joints' bodies); either way
// each lane holds the bits Eigen's scalar product gives.
template <class Q>
[[gnu::always_inline]] inline FourVectors rotate(const Q& qx, const Q& qy, const Q& qz, const Q& qw,
                                                 const FourVectors& v) {
  FourDoubles ux = qy * v.z - qz * v.y;
  FourDoubles uy = qz * v.x - qx * v.z;
  FourDoubles uz = qx * v.y - qy * v.x;
  ux += ux;
  uy += uy;
  uz += uz;
  return {v.x + qw * ux + (qy * uz - qz * uy), v.y + qw * uy + (qz * ux - qx * uz),
          v.z + qw * uz + (qx * uy - qy * ux)};
}

}  // namespace softstep
