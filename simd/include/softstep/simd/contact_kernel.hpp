// Soft contacts in lanes: one lane is one manifold of up to 4 points (the talk's soft contact,
// DESIGN.md and architecture-milestone-2.md section 4.6).
//   normal row   per point, along the manifold normal n, unilateral (impulse >= 0). Apart
//                (separation s > 0) it is speculative: the gap may close within the sub-step,
//                no further. Penetrating, while solving it is the contact spring (hertz,
//                damping ratio) whose push-out speed is bounded; while relaxing it has no bias.
//   friction     two tangent rows per point, solved after the normals, their impulse capped
//                together by friction * that point's normal impulse (a disk, the cone's exact
//                section; a per-row box would let the diagonal carry sqrt(2) too much).
//   rolling      three angular rows on w_B - w_A, capped by rolling_resistance * the
//                manifold's total normal impulse.
//   restitution  after the sub-steps, per point closing faster than the threshold at the step
//                start: drives the normal speed to -restitution * that speed.
// The Jacobians use the anchors of the step start (fixed within the step, as Box2D and Box3D
// do); the separation follows the bodies' motion since the step start, with the anchors
// turned by each body's rotation. A round shape (radius > 0: the caller's anchor is its core,
// a sphere's centre) turns only its core: its surface point stays `radius` along the normal
// from the core, so a rolling wheel's contact does not rise off the ground as the wheel turns.
// The lever arms r_a, r_b are the surface points (core_a + radius_a n, core_b - radius_b n).
#pragma once

#include <cstdint>

#include "softstep/simd/angles.hpp"
#include "softstep/simd/joint_lanes.hpp"
#include "softstep/simd/parts/axis_part.hpp"

namespace softstep::simd {

inline constexpr int kContactPoints = 4;

// Which rows a group of contacts runs; runs of groups are uniform in it.
enum ContactFeature : std::uint32_t {
  kContactFriction = 1u << 0,  // some lane has friction > 0
  kContactRolling = 1u << 1,   // some lane has rolling resistance > 0
};
inline constexpr std::uint32_t kContactSignatures = 4;

// The contact spring for one sub-step and what else every contact shares.
struct ContactContext {
  float bias_rate, mass_scale, impulse_scale;  // softness.hpp, from ContactSettings
  float max_push_out_speed;                    // m/s
  float restitution_threshold;                 // m/s
};

template <int W>
struct alignas(kLaneAlign<W>) ContactPointLanes {
  // Written by core each step (world frame, at the step start):
  float r_a[3][W];            // contact point on A - centre of A, m
  float r_b[3][W];            // contact point on B - centre of B, m
  float base_separation[W];   // separation - n . (core_b - core_a): add n . (x_B - x_A)
  float normal_impulse[W];    // accumulated, N s (warm start on entry)
  float tangent_impulse[2][W];
  // Prepared:
  float normal_mass[W];  // 1 / K along n; 0 for an unused point
  float tangent_mass[2][W];
  float max_normal_impulse[W];
  float relative_velocity[W];  // n . (v_B - v_A) at the point, at the step start
};

template <int W>
struct alignas(kLaneAlign<W>) ContactLanes {
  std::uint32_t id[W];  // the manifold's index in the step's span, kPaddingLane if none
  std::int32_t body_a[W];
  std::int32_t body_b[W];
  float point_count[W];  // points of this lane's manifold (0 for padding)
  float normal[3][W];
  float tangent[2][3][W];
  float friction[W];
  float restitution[W];
  float rolling_resistance[W];
  float tangent_speed[2][W];
  float radius_a[W];            // m, >= 0: core_a = r_a - radius_a n (0: the arm is the core)
  float radius_b[W];            // m, >= 0: core_b = r_b + radius_b n
  float rolling_impulse[3][W];  // on B, N m s
  float rolling_mass[6][W];     // (I_A^-1 + I_B^-1)^-1, prepared
  ContactPointLanes<W> point[kContactPoints];
  int points;  // the most points of any lane: the point loops stop here
};

template <class L>
SOFTSTEP_INLINE JointBodies<L> gather_contact(const ContactLanes<kWidth<L>>& g,
                                              const BodyArrays& bodies) {
  return {gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_a),
          gather_body<L>(bodies.velocity, bodies.delta, bodies.mass, g.body_b),
          {},
          {},
          {}};
}

// The manifold's normal and tangents.
template <class L>
struct ContactFrame {
  Vec3<L> n, t1, t2;
};

template <class L>
SOFTSTEP_INLINE ContactFrame<L> load_frame(const ContactLanes<kWidth<L>>& g) {
  return {load3<L>(g.normal), load3<L>(g.tangent[0]), load3<L>(g.tangent[1])};
}

// Points the bodies' arms at point p's fixed anchors.
template <class L>
SOFTSTEP_INLINE void aim_at(JointBodies<L>& j, const ContactPointLanes<kWidth<L>>& p) {
  j.r_a = load3<L>(p.r_a);
  j.r_b = load3<L>(p.r_b);
}

template <class L, std::uint32_t kSignature>
SOFTSTEP_INLINE void prepare_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies) {
  JointBodies<L> j = gather_contact<L>(g, bodies);
  const auto [n, t1, t2] = load_frame<L>(g);
  const L count = load<L>(g.point_count);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    aim_at(j, p);
    const auto used = L(static_cast<float>(i)) < count;
    const auto mass = [&](const Vec3<L>& axis) {
      return select(used,
                    axial_mass(j.a.inv_mass, j.a.inv_inertia, j.r_a, j.b.inv_mass,
                               j.b.inv_inertia, j.r_b, axis),
                    L(0.0f));
    };
    store_lanes(p.normal_mass, mass(n));
    if constexpr ((kSignature & kContactFriction) != 0) {
      store_lanes(p.tangent_mass[0], mass(t1));
      store_lanes(p.tangent_mass[1], mass(t2));
    }
    store_lanes(p.max_normal_impulse, L(0.0f));
    store_lanes(p.relative_velocity, dot(n, relative_velocity(j)));
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    const Mat3Sym<L> m = inverse_or_zero(j.a.inv_inertia + j.b.inv_inertia);
    const L entries[6] = {m.xx, m.yy, m.zz, m.xy, m.xz, m.yz};
    for (int k = 0; k < 6; ++k) store_lanes(g.rolling_mass[k], entries[k]);
  }
}

template <class L, std::uint32_t kSignature>
SOFTSTEP_INLINE void warm_start_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies) {
  JointBodies<L> j = gather_contact<L>(g, bodies);
  const auto [n, t1, t2] = load_frame<L>(g);
  for (int i = 0; i < g.points; ++i) {
    const auto& p = g.point[i];
    aim_at(j, p);
    Vec3<L> impulse = load<L>(p.normal_impulse) * n;
    if constexpr ((kSignature & kContactFriction) != 0) {
      impulse = mul_add(load<L>(p.tangent_impulse[0]), t1, impulse);
      impulse = mul_add(load<L>(p.tangent_impulse[1]), t2, impulse);
    }
    apply_impulse(j, impulse);
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    apply_angular_impulse(j, load3<L>(g.rolling_impulse));
  }
  scatter_joint(g, bodies, j);
}

// The normal row's impulse change at one point (see the top of the file for the modes).
template <class L, bool kUseBias>
SOFTSTEP_INLINE L contact_normal_impulse(const L& vn, const L& separation, const L& m_eff,
                                         const L& accumulated, const SubstepContext& ctx,
                                         const ContactContext& cc) {
  const auto apart = separation > L(0.0f);
  L bias = select(apart, separation * L(ctx.inv_h), L(0.0f));
  L mass_scale(1.0f);
  L impulse_scale(0.0f);
  if constexpr (kUseBias) {
    const L push = max_lanes(L(cc.bias_rate) * separation, L(0.0f) - L(cc.max_push_out_speed));
    bias = select(apart, bias, push);
    mass_scale = select(apart, mass_scale, L(cc.mass_scale));
    impulse_scale = select(apart, impulse_scale, L(cc.impulse_scale));
  }
  const L raw =
      fmadd(L(0.0f) - mass_scale * m_eff, vn + bias, L(0.0f) - impulse_scale * accumulated);
  return max_lanes(accumulated + raw, L(0.0f)) - accumulated;
}

template <class L, std::uint32_t kSignature, bool kUseBias>
SOFTSTEP_INLINE void solve_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies,
                                    const SubstepContext& ctx, const ContactContext& cc) {
  JointBodies<L> j = gather_contact<L>(g, bodies);
  const Vec3<L> n = load3<L>(g.normal);
  // The separation follows the turned cores: n . (R_B core_b - R_A core_a). Written as
  // (R_B^T n) . core_b - (R_A^T n) . core_a, the two rotations are per lane, not per point
  // (for a 4-point manifold 2 instead of 8, a tenth of the kernel's work; the rotate() map's
  // transpose is exactly the rotate() of the conjugate, unit or not). With core = arm +
  // offset n, each body's offset term (R^T n) . n * offset is per lane as well.
  const Vec3<L> n_in_a = rotate(conjugate(j.a.dq), n);
  const Vec3<L> n_in_b = rotate(conjugate(j.b.dq), n);
  // How far the centres moved towards each other along n since the step start, and the
  // round shapes' offsets along the turned normal.
  const L shift = dot(n, j.b.dp - j.a.dp) + load<L>(g.radius_b) * dot(n_in_b, n) +
                  load<L>(g.radius_a) * dot(n_in_a, n);
  [[maybe_unused]] L total_normal(0.0f);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    aim_at(j, p);
    // The base and the turned arms' term are both about the distance between the centres
    // (a metre for stacked boxes) and cancel: summed first, the small shift keeps its bits.
    // (The order matters more than it should: a 10-box wall at 30 Hz holds to 0.8 mm summed
    // so, and crept 2.4 mm summed base + shift + arms: tests/contacts/pyramid_test.cpp.)
    const L separation =
        (load<L>(p.base_separation) + (dot(n_in_b, j.r_b) - dot(n_in_a, j.r_a))) + shift;
    const L accumulated = load<L>(p.normal_impulse);
    const L dp = contact_normal_impulse<L, kUseBias>(dot(n, relative_velocity(j)), separation,
                                                     load<L>(p.normal_mass), accumulated, ctx, cc);
    const L next = accumulated + dp;
    store_lanes(p.normal_impulse, next);
    store_lanes(p.max_normal_impulse, max_lanes(load<L>(p.max_normal_impulse), next));
    if constexpr ((kSignature & kContactRolling) != 0) total_normal = total_normal + next;
    apply_impulse(j, dp * n);
  }
  if constexpr ((kSignature & kContactFriction) != 0) {
    const Vec3<L> t1 = load3<L>(g.tangent[0]);
    const Vec3<L> t2 = load3<L>(g.tangent[1]);
    const L friction = load<L>(g.friction);
    const L speed1 = load<L>(g.tangent_speed[0]);
    const L speed2 = load<L>(g.tangent_speed[1]);
    for (int i = 0; i < g.points; ++i) {
      auto& p = g.point[i];
      aim_at(j, p);
      const Vec3<L> dv = relative_velocity(j);
      const L old1 = load<L>(p.tangent_impulse[0]);
      const L old2 = load<L>(p.tangent_impulse[1]);
      L new1 = fmadd(L(0.0f) - load<L>(p.tangent_mass[0]), dot(t1, dv) - speed1, old1);
      L new2 = fmadd(L(0.0f) - load<L>(p.tangent_mass[1]), dot(t2, dv) - speed2, old2);
      // The disk clamp: scale both back onto the circle of radius friction * normal impulse.
      const L cap = friction * load<L>(p.normal_impulse);
      const L length2 = fmadd(new1, new1, new2 * new2);
      const auto over = length2 > cap * cap;
      const L scale = select(over, cap / sqrt_lanes(select(over, length2, L(1.0f))), L(1.0f));
      new1 = new1 * scale;
      new2 = new2 * scale;
      store_lanes(p.tangent_impulse[0], new1);
      store_lanes(p.tangent_impulse[1], new2);
      apply_impulse(j, mul_add(new2 - old2, t2, (new1 - old1) * t1));
    }
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    const Mat3Sym<L> m{load<L>(g.rolling_mass[0]), load<L>(g.rolling_mass[1]),
                       load<L>(g.rolling_mass[2]), load<L>(g.rolling_mass[3]),
                       load<L>(g.rolling_mass[4]), load<L>(g.rolling_mass[5])};
    const Vec3<L> old = load3<L>(g.rolling_impulse);
    Vec3<L> next = old - m * (j.b.w - j.a.w);
    const L cap = load<L>(g.rolling_resistance) * total_normal;
    const L length2 = dot(next, next);
    const auto over = length2 > cap * cap;
    next = select(over, cap / sqrt_lanes(select(over, length2, L(1.0f))), L(1.0f)) * next;
    store3<L>(g.rolling_impulse, next);
    apply_angular_impulse(j, next - old);
  }
  scatter_joint(g, bodies, j);
}

// After the sub-steps: the normal speed of each point that closed faster than the threshold
// at the step start and touched during the step becomes -restitution times that speed.
template <class L>
SOFTSTEP_INLINE void restitute_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies,
                                        const ContactContext& cc) {
  JointBodies<L> j = gather_contact<L>(g, bodies);
  const Vec3<L> n = load3<L>(g.normal);
  const L restitution = load<L>(g.restitution);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    aim_at(j, p);
    const L approach = load<L>(p.relative_velocity);
    const auto bounces = approach < L(0.0f - cc.restitution_threshold) &&
                         load<L>(p.max_normal_impulse) > L(0.0f) && restitution > L(0.0f);
    const L accumulated = load<L>(p.normal_impulse);
    const L vn = dot(n, relative_velocity(j));
    const L raw = (L(0.0f) - load<L>(p.normal_mass)) * fmadd(restitution, approach, vn);
    const L dp = select(bounces, max_lanes(accumulated + raw, L(0.0f)) - accumulated, L(0.0f));
    store_lanes(p.normal_impulse, accumulated + dp);
    apply_impulse(j, dp * n);
  }
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
