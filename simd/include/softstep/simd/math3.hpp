// Vec3, symmetric Mat3 and Quat whose components are lanes: one instance holds W vectors.
// Each formula is written once; `float` gives the scalar solver, batches the wide ones.
#pragma once

#include "softstep/simd/lanes.hpp"

namespace softstep::simd {

template <class L>
struct Vec3 {
  L x, y, z;
};

template <class L>
SOFTSTEP_INLINE Vec3<L> operator+(const Vec3<L>& a, const Vec3<L>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class L>
SOFTSTEP_INLINE Vec3<L> operator-(const Vec3<L>& a, const Vec3<L>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class L>
SOFTSTEP_INLINE Vec3<L> operator-(const Vec3<L>& a) {
  return {L(0.0f) - a.x, L(0.0f) - a.y, L(0.0f) - a.z};
}
template <class L>
SOFTSTEP_INLINE Vec3<L> operator*(const L& s, const Vec3<L>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
// a + s * b, fused per component
template <class L>
SOFTSTEP_INLINE Vec3<L> mul_add(const L& s, const Vec3<L>& b, const Vec3<L>& a) {
  return {fmadd(s, b.x, a.x), fmadd(s, b.y, a.y), fmadd(s, b.z, a.z)};
}
template <class L>
SOFTSTEP_INLINE L dot(const Vec3<L>& a, const Vec3<L>& b) {
  return fmadd(a.x, b.x, fmadd(a.y, b.y, a.z * b.z));
}
template <class L>
SOFTSTEP_INLINE Vec3<L> cross(const Vec3<L>& a, const Vec3<L>& b) {
  return {fmadd(a.y, b.z, L(0.0f) - a.z * b.y), fmadd(a.z, b.x, L(0.0f) - a.x * b.z),
          fmadd(a.x, b.y, L(0.0f) - a.y * b.x)};
}
// Symmetric 3x3 matrix: inverse inertia tensors and the 3x3 effective-mass matrix K of a
// ball joint are symmetric, so six lanes hold them.
template <class L>
struct Mat3Sym {
  L xx, yy, zz, xy, xz, yz;
};

template <class L>
SOFTSTEP_INLINE Vec3<L> operator*(const Mat3Sym<L>& m, const Vec3<L>& v) {
  return {fmadd(m.xx, v.x, fmadd(m.xy, v.y, m.xz * v.z)),
          fmadd(m.xy, v.x, fmadd(m.yy, v.y, m.yz * v.z)),
          fmadd(m.xz, v.x, fmadd(m.yz, v.y, m.zz * v.z))};
}
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> operator+(const Mat3Sym<L>& a, const Mat3Sym<L>& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}

// skew(r)^T * I * skew(r) for symmetric I: the rotational part r x (I (r x .)) that a
// point impulse at offset r adds to the effective-mass matrix K = J M^-1 J^T.
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> rotational_mass_term(const Mat3Sym<L>& inv_i, const Vec3<L>& r) {
  // With S = skew(r) (S p = r x p), the anchor velocity an impulse p causes through rotation
  // is -r x I (r x p) = S^T I S p. Entry (i, j) is (S e_i) . I (S e_j): symmetric by
  // construction, so only six dot products are formed.
  const Vec3<L> c0 = inv_i * Vec3<L>{L(0.0f), r.z, L(0.0f) - r.y};  // I * (S e_x)
  const Vec3<L> c1 = inv_i * Vec3<L>{L(0.0f) - r.z, L(0.0f), r.x};  // I * (S e_y)
  const Vec3<L> c2 = inv_i * Vec3<L>{r.y, L(0.0f) - r.x, L(0.0f)};  // I * (S e_z)
  // (S^T A)_ij = (S e_i) . (A e_j) with S e_x = (0, z, -y), S e_y = (-z, 0, x), S e_z = (y, -x, 0)
  const Vec3<L> s0{L(0.0f), r.z, L(0.0f) - r.y};
  const Vec3<L> s1{L(0.0f) - r.z, L(0.0f), r.x};
  const Vec3<L> s2{r.y, L(0.0f) - r.x, L(0.0f)};
  return {dot(s0, c0), dot(s1, c1), dot(s2, c2), dot(s0, c1), dot(s0, c2), dot(s1, c2)};
}

// 1/d where d > 0, else 0 (no division by zero in the lanes that discard it).
template <class L>
SOFTSTEP_INLINE L reciprocal_if_positive(const L& d) {
  const auto positive = d > L(0.0f);
  return select(positive, L(1.0f) / select(positive, d, L(1.0f)), L(0.0f));
}

// Inverse of a symmetric matrix m = L D L^T (unit lower-triangular L, diagonal D), zero where
// a pivot is not positive. For a positive definite m this is backward stable: its error grows
// as cond(m) x 6e-8. The cofactors below lose every digit of the determinant once it falls to
// ~1e-7 (their terms are of order 1): an angular lock on a body of principal moments 6e5 apart
// came out indefinite, and the body flew off its joint.
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> ldl_inverse_or_zero(const Mat3Sym<L>& m) {
  const L e1 = reciprocal_if_positive(m.xx);
  const L l21 = m.xy * e1, l31 = m.xz * e1;
  const L d2 = m.yy - l21 * m.xy;
  const L e2 = reciprocal_if_positive(d2);
  const L t = m.yz - l21 * m.xz;  // d2 l32
  const L l32 = t * e2;
  const L d3 = m.zz - l31 * m.xz - l32 * t;
  const L e3 = reciprocal_if_positive(d3);
  // inverse(L)'s rows: (1, 0, 0), (a, 1, 0), (b, c, 1); m^-1 = sum_i e_i row_i^T row_i.
  const L a = L(0.0f) - l21, c = L(0.0f) - l32, b = l21 * l32 - l31;
  const auto ok = m.xx > L(0.0f) && d2 > L(0.0f) && d3 > L(0.0f);
  const L keep = select(ok, L(1.0f), L(0.0f));
  const L e3b = e3 * b, e3c = e3 * c;
  return {keep * (e1 + e2 * a * a + e3b * b),
          keep * (e2 + e3c * c),
          keep * e3,
          keep * (e2 * a + e3b * c),
          keep * e3b,
          keep * e3c};
}

// Inverse of a symmetric positive semi-definite matrix by cofactors (by the factorization above
// where it is ill-conditioned), scaled first by its largest diagonal entry: the determinant is a
// product of three entries and would leave the float range (1e-38 .. 3e38) long before the entries
// do (a 1e13 kg body, a 1e-12 kg one). A singular matrix (a constraint between bodies that cannot
// move, a padding lane) yields zero, so the constraint applies no impulse instead of a NaN.
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> inverse_or_zero(const Mat3Sym<L>& k) {
  const L scale = max_lanes(k.xx, max_lanes(k.yy, k.zz));
  const auto usable = scale > L(0.0f);
  const L inv_scale = select(usable, L(1.0f) / select(usable, scale, L(1.0f)), L(0.0f));
  const Mat3Sym<L> m{k.xx * inv_scale, k.yy * inv_scale, k.zz * inv_scale,
                     k.xy * inv_scale, k.xz * inv_scale, k.yz * inv_scale};
  const L c_xx = fmadd(m.yy, m.zz, L(0.0f) - m.yz * m.yz);
  const L c_xy = fmadd(m.xz, m.yz, L(0.0f) - m.xy * m.zz);
  const L c_xz = fmadd(m.xy, m.yz, L(0.0f) - m.xz * m.yy);
  const L det = fmadd(m.xx, c_xx, fmadd(m.xy, c_xy, m.xz * c_xz));
  const auto ok = det > L(0.0f);
  // inverse(k) = inverse(m) / scale
  const L f = select(ok, inv_scale / select(ok, det, L(1.0f)), L(0.0f));
  const L c_yy = fmadd(m.xx, m.zz, L(0.0f) - m.xz * m.xz);
  const L c_yz = fmadd(m.xy, m.xz, L(0.0f) - m.xx * m.yz);
  const L c_zz = fmadd(m.xx, m.yy, L(0.0f) - m.xy * m.xy);
  Mat3Sym<L> inverse{c_xx * f, c_yy * f, c_zz * f, c_xy * f, c_xz * f, c_yz * f};
  // Where the scaled determinant is small (or not positive: rounding can make it so for a
  // positive definite m) the factorization takes over. Elsewhere the cofactors stay, bit for
  // bit: at 1e-6 their error is below ~1 %, and no joint of the golden scenes comes near it.
  const auto ill_conditioned = usable && !(det > L(1e-6f));
  if (any_lane(ill_conditioned)) {
    const Mat3Sym<L> careful = ldl_inverse_or_zero(m);
    inverse = {select(ill_conditioned, careful.xx * inv_scale, inverse.xx),
               select(ill_conditioned, careful.yy * inv_scale, inverse.yy),
               select(ill_conditioned, careful.zz * inv_scale, inverse.zz),
               select(ill_conditioned, careful.xy * inv_scale, inverse.xy),
               select(ill_conditioned, careful.xz * inv_scale, inverse.xz),
               select(ill_conditioned, careful.yz * inv_scale, inverse.yz)};
  }
  return inverse;
}

// Unit quaternion (x, y, z, w).
template <class L>
struct Quat {
  L x, y, z, w;
};

// q * v * q^-1, as v + 2w (u x v) + 2 u x (u x v) with u = (x, y, z).
template <class L>
SOFTSTEP_INLINE Vec3<L> rotate(const Quat<L>& q, const Vec3<L>& v) {
  const Vec3<L> u{q.x, q.y, q.z};
  const Vec3<L> t = L(2.0f) * cross(u, v);
  return mul_add(q.w, t, v + cross(u, t));
}

// Advance a rotation by angular velocity w (world frame) over h: q += h/2 (w,0) * q, then
// renormalize. First order, like the position update of semi-implicit Euler.
template <class L>
SOFTSTEP_INLINE Quat<L> integrate_rotation(const Quat<L>& q, const Vec3<L>& w, const L& h) {
  const L hh = L(0.5f) * h;
  const Vec3<L> a{hh * w.x, hh * w.y, hh * w.z};
  Quat<L> r{fmadd(a.x, q.w, fmadd(a.y, q.z, fmadd(L(0.0f) - a.z, q.y, q.x))),
            fmadd(a.y, q.w, fmadd(a.z, q.x, fmadd(L(0.0f) - a.x, q.z, q.y))),
            fmadd(a.z, q.w, fmadd(a.x, q.y, fmadd(L(0.0f) - a.y, q.x, q.z))),
            fmadd(L(0.0f) - a.x, q.x, fmadd(L(0.0f) - a.y, q.y, fmadd(L(0.0f) - a.z, q.z, q.w)))};
  const L len2 = fmadd(r.x, r.x, fmadd(r.y, r.y, fmadd(r.z, r.z, r.w * r.w)));
  const L inv_len = L(1.0f) / sqrt_lanes(len2);
  return {r.x * inv_len, r.y * inv_len, r.z * inv_len, r.w * inv_len};
}

}  // namespace softstep::simd
