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
//
// Every row is solved in the manifold's own frame (t1, t2, n), a rotation (the packing makes n
// unit): the arms are stored in it, the bodies' inverse inertias are turned into it once per
// step (prepare), and each pass turns the bodies' velocities into it on entry. There the rows'
// axes are the unit axes, so a row's velocity and its impulse's effect take a few products
// where the world frame took a cross product and an inertia product each: per point and pass
// about half the arithmetic, for 14 more lanes per lane group (the frame inertias and inverse
// masses) and no mass records read by the iterations. (So the contacts keep the step-start
// inertia through the step, where the joints' rows see the geometric inertia refreshed after
// the first sub-step of a step with new joints, step.cpp.) Only each body's velocity change
// goes back to the world frame (a lane that applies nothing leaves its bodies' velocities bit
// for bit, but for a -0 that may come back +0).
#pragma once

#include <cstdint>

#include "softstep/simd/angles.hpp"
#include "softstep/simd/joint_lanes.hpp"
#include "softstep/simd/parts/rows.hpp"

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
  // Written by core each step, at the step start; the arms in the manifold's frame (t1, t2, n):
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
  float normal[3][W];    // world frame, unit; with the tangents, the manifold's frame
  float tangent[2][3][W];
  float friction[W];
  float restitution[W];
  float rolling_resistance[W];
  float tangent_speed[2][W];
  float radius_a[W];            // m, >= 0: core_a = r_a - radius_a n (0: the arm is the core)
  float radius_b[W];            // m, >= 0: core_b = r_b + radius_b n
  float rolling_impulse[3][W];  // on B, N m s, in the manifold's frame
  // Prepared, in the manifold's frame:
  float rolling_mass[6][W];  // (I_A^-1 + I_B^-1)^-1
  float inertia_a[6][W];     // I_A^-1 (xx yy zz xy xz yz)
  float inertia_b[6][W];
  float inv_mass_a[W];  // 1/kg (the iterations read no mass record)
  float inv_mass_b[W];
  ContactPointLanes<W> point[kContactPoints];
  int points;  // the most points of any lane: the point loops stop here
};

// The manifold's frame: its rows t1, t2, n (R), a rotation.
template <class L>
struct ContactFrame {
  Vec3<L> n, t1, t2;
};

template <class L>
SOFTSTEP_INLINE ContactFrame<L> load_frame(const ContactLanes<kWidth<L>>& g) {
  return {load3<L>(g.normal), load3<L>(g.tangent[0]), load3<L>(g.tangent[1])};
}

// R x: a world vector in the frame.
template <class L>
SOFTSTEP_INLINE Vec3<L> to_frame(const ContactFrame<L>& f, const Vec3<L>& x) {
  return {dot(f.t1, x), dot(f.t2, x), dot(f.n, x)};
}

// R^T x: a frame vector in the world.
template <class L>
SOFTSTEP_INLINE Vec3<L> from_frame(const ContactFrame<L>& f, const Vec3<L>& x) {
  return mul_add(x.z, f.n, mul_add(x.y, f.t2, x.x * f.t1));
}

// R M R^T: a world inverse inertia in the frame.
template <class L>
SOFTSTEP_INLINE Mat3Sym<L> to_frame(const ContactFrame<L>& f, const Mat3Sym<L>& m) {
  const Vec3<L> m1 = m * f.t1;
  const Vec3<L> m2 = m * f.t2;
  const Vec3<L> mn = m * f.n;
  return {dot(f.t1, m1), dot(f.t2, m2), dot(f.n, mn), dot(f.t1, m2), dot(f.t1, mn), dot(f.t2, mn)};
}

template <class L>
SOFTSTEP_INLINE Mat3Sym<L> load_sym(const float (&a)[6][kWidth<L>]) {
  return {load<L>(a[0]), load<L>(a[1]), load<L>(a[2]), load<L>(a[3]), load<L>(a[4]), load<L>(a[5])};
}

template <class L>
SOFTSTEP_INLINE void store_sym(float (&a)[6][kWidth<L>], const Mat3Sym<L>& m) {
  const L entries[6] = {m.xx, m.yy, m.zz, m.xy, m.xz, m.yz};
  for (int k = 0; k < 6; ++k) store_lanes(a[k], entries[k]);
}

// One body of each lane in the manifold's frame.
template <class L>
struct FrameBody {
  Vec3<L> v, w;    // now
  Vec3<L> v0, w0;  // on entry: only the change goes back to the world
  L inv_mass;
  Mat3Sym<L> inv_inertia;
};

// Both bodies of each lane: as gathered (world; the delta records where the pass follows the
// separation) and in the frame.
template <class L>
struct ContactBodies {
  JointBodies<L> world;
  ContactFrame<L> f;
  FrameBody<L> a, b;
};

// Whether a pass reads the delta records besides the velocity records (the solve, for the
// separation). No pass after the prepare reads the mass records: the lanes hold what it needs.
enum class ContactGather { Velocity, VelocityAndDelta };

template <class L, ContactGather kGather>
SOFTSTEP_INLINE void gather_contact_body(BodyLanes<L>& out, const BodyArrays& bodies,
                                         const std::int32_t* index,
                                         const float (&inv_mass)[kWidth<L>]) {
  gather_velocity_into(out, bodies.velocity, index);
  if constexpr (kGather == ContactGather::VelocityAndDelta)
    gather_delta_into(out, bodies.delta, index);
  out.inv_mass = load<L>(inv_mass);
  out.movable = out.inv_mass > L(0.0f);
}

template <class L>
SOFTSTEP_INLINE void enter_frame(FrameBody<L>& s, const BodyLanes<L>& body,
                                 const ContactFrame<L>& f, const Mat3Sym<L>& inv_inertia) {
  s.v = to_frame(f, body.v);
  s.w = to_frame(f, body.w);
  s.v0 = s.v;
  s.w0 = s.w;
  s.inv_mass = body.inv_mass;
  s.inv_inertia = inv_inertia;
}

template <class L, ContactGather kGather>
SOFTSTEP_INLINE ContactBodies<L> enter_contact(const ContactLanes<kWidth<L>>& g,
                                               const BodyArrays& bodies) {
  ContactBodies<L> c;  // filled in place (gather_body_into says why)
  gather_contact_body<L, kGather>(c.world.a, bodies, g.body_a, g.inv_mass_a);
  gather_contact_body<L, kGather>(c.world.b, bodies, g.body_b, g.inv_mass_b);
  c.f = load_frame<L>(g);
  enter_frame(c.a, c.world.a, c.f, load_sym<L>(g.inertia_a));
  enter_frame(c.b, c.world.b, c.f, load_sym<L>(g.inertia_b));
  return c;
}

// Adds each body's velocity change back in the world frame and writes the velocities.
template <class L>
SOFTSTEP_INLINE void leave_contact(const ContactLanes<kWidth<L>>& g, const BodyArrays& bodies,
                                   ContactBodies<L>& c) {
  c.world.a.v = c.world.a.v + from_frame(c.f, c.a.v - c.a.v0);
  c.world.a.w = c.world.a.w + from_frame(c.f, c.a.w - c.a.w0);
  c.world.b.v = c.world.b.v + from_frame(c.f, c.b.v - c.b.v0);
  c.world.b.w = c.world.b.w + from_frame(c.f, c.b.w - c.b.w0);
  scatter_joint(g, bodies, c.world);
}

// Along n (the frame's z) the speed of the point at arm r: (v + w x r).z.
template <class L>
SOFTSTEP_INLINE L normal_speed(const FrameBody<L>& s, const Vec3<L>& r) {
  return fmadd(s.w.x, r.y, s.v.z) - s.w.y * r.x;
}

// The relative normal speed of B's point from A's.
template <class L>
SOFTSTEP_INLINE L normal_speed(const ContactBodies<L>& c, const Vec3<L>& r_a, const Vec3<L>& r_b) {
  return normal_speed(c.b, r_b) - normal_speed(c.a, r_a);
}

// An impulse `amount` along n at arm r (B takes +dp, A -dp): r x n is (r.y, -r.x, 0).
template <class L>
SOFTSTEP_INLINE void apply_normal(FrameBody<L>& s, const Vec3<L>& r, const L& amount) {
  s.v.z = fmadd(s.inv_mass, amount, s.v.z);
  const L c0 = r.y * amount;
  const L c1 = (L(0.0f) - r.x) * amount;
  const Mat3Sym<L>& m = s.inv_inertia;
  s.w.x = fmadd(m.xx, c0, fmadd(m.xy, c1, s.w.x));
  s.w.y = fmadd(m.xy, c0, fmadd(m.yy, c1, s.w.y));
  s.w.z = fmadd(m.xz, c0, fmadd(m.yz, c1, s.w.z));
}

// The speed of the point at arm r along t1 and t2 (the frame's x and y): (v + w x r).xy.
template <class L>
SOFTSTEP_INLINE void tangent_speeds(const FrameBody<L>& s, const Vec3<L>& r, L& x, L& y) {
  x = fmadd(s.w.y, r.z, s.v.x) - s.w.z * r.y;
  y = fmadd(s.w.z, r.x, s.v.y) - s.w.x * r.z;
}

// An impulse (x, y, 0) at arm r: r x (x, y, 0) = (-r.z y, r.z x, r.x y - r.y x).
template <class L>
SOFTSTEP_INLINE void apply_tangent(FrameBody<L>& s, const Vec3<L>& r, const L& x, const L& y) {
  s.v.x = fmadd(s.inv_mass, x, s.v.x);
  s.v.y = fmadd(s.inv_mass, y, s.v.y);
  const Vec3<L> turn{(L(0.0f) - r.z) * y, r.z * x, fmadd(r.x, y, L(0.0f) - r.y * x)};
  s.w = s.w + s.inv_inertia * turn;
}

// A row's K about arm r along a frame axis whose r x axis is u, for one body.
template <class L>
SOFTSTEP_INLINE L angular_mass(const FrameBody<L>& s, const Vec3<L>& u) {
  return dot(u, s.inv_inertia * u);
}

template <class L, std::uint32_t kSignature>
SOFTSTEP_INLINE void prepare_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies) {
  ContactBodies<L> c;
  gather_body_into(c.world.a, bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  gather_body_into(c.world.b, bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  c.f = load_frame<L>(g);
  enter_frame(c.a, c.world.a, c.f, to_frame(c.f, c.world.a.inv_inertia));
  enter_frame(c.b, c.world.b, c.f, to_frame(c.f, c.world.b.inv_inertia));
  store_lanes(g.inv_mass_a, c.a.inv_mass);
  store_lanes(g.inv_mass_b, c.b.inv_mass);
  store_sym<L>(g.inertia_a, c.a.inv_inertia);
  store_sym<L>(g.inertia_b, c.b.inv_inertia);
  const L linear = c.a.inv_mass + c.b.inv_mass;
  const L count = load<L>(g.point_count);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    const Vec3<L> ra = load3<L>(p.r_a);
    const Vec3<L> rb = load3<L>(p.r_b);
    const auto used = L(static_cast<float>(i)) < count;
    // r x axis for the axes n, t1, t2: (r.y, -r.x, 0), (0, r.z, -r.y), (-r.z, 0, r.x).
    const auto mass = [&](const Vec3<L>& ua, const Vec3<L>& ub) {
      return select(used, inverse_or_zero(linear + angular_mass(c.a, ua) + angular_mass(c.b, ub)),
                    L(0.0f));
    };
    const L zero(0.0f);
    store_lanes(p.normal_mass, mass({ra.y, zero - ra.x, zero}, {rb.y, zero - rb.x, zero}));
    if constexpr ((kSignature & kContactFriction) != 0) {
      store_lanes(p.tangent_mass[0], mass({zero, ra.z, zero - ra.y}, {zero, rb.z, zero - rb.y}));
      store_lanes(p.tangent_mass[1], mass({zero - ra.z, zero, ra.x}, {zero - rb.z, zero, rb.x}));
    }
    store_lanes(p.max_normal_impulse, zero);
    store_lanes(p.relative_velocity, normal_speed(c, ra, rb));
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    store_sym<L>(g.rolling_mass, inverse_or_zero(c.a.inv_inertia + c.b.inv_inertia));
  }
}

template <class L, std::uint32_t kSignature>
SOFTSTEP_INLINE void warm_start_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies) {
  ContactBodies<L> c = enter_contact<L, ContactGather::Velocity>(g, bodies);
  // Each point's impulse (t1, t2, n parts) summed, and its moment about each centre.
  Vec3<L> impulse{L(0.0f), L(0.0f), L(0.0f)};
  Vec3<L> moment_a = impulse;
  Vec3<L> moment_b = impulse;
  for (int i = 0; i < g.points; ++i) {
    const auto& p = g.point[i];
    Vec3<L> point{L(0.0f), L(0.0f), load<L>(p.normal_impulse)};
    if constexpr ((kSignature & kContactFriction) != 0) {
      point.x = load<L>(p.tangent_impulse[0]);
      point.y = load<L>(p.tangent_impulse[1]);
    }
    impulse = impulse + point;
    moment_a = moment_a + cross(load3<L>(p.r_a), point);
    moment_b = moment_b + cross(load3<L>(p.r_b), point);
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    const Vec3<L> rolling = load3<L>(g.rolling_impulse);
    moment_a = moment_a + rolling;
    moment_b = moment_b + rolling;
  }
  c.a.v = mul_add(L(0.0f) - c.a.inv_mass, impulse, c.a.v);
  c.a.w = c.a.w - c.a.inv_inertia * moment_a;
  c.b.v = mul_add(c.b.inv_mass, impulse, c.b.v);
  c.b.w = c.b.w + c.b.inv_inertia * moment_b;
  leave_contact(g, bodies, c);
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
  ContactBodies<L> c = enter_contact<L, ContactGather::VelocityAndDelta>(g, bodies);
  const JointBodies<L>& j = c.world;
  // The separation follows the turned cores: n . (R_B core_b - R_A core_a). Written as
  // (R_B^T n) . core_b - (R_A^T n) . core_a, the two rotations are per lane, not per point
  // (for a 4-point manifold 2 instead of 8, a tenth of the kernel's work; the rotate() map's
  // transpose is exactly the rotate() of the conjugate, unit or not), and turned into the
  // frame like the arms. With core = arm + offset n, each body's offset term
  // (R^T n) . n * offset is per lane as well.
  const Vec3<L> n_in_a = to_frame(c.f, rotate(conjugate(j.a.dq), c.f.n));
  const Vec3<L> n_in_b = to_frame(c.f, rotate(conjugate(j.b.dq), c.f.n));
  // How far the centres moved towards each other along n since the step start, and the
  // round shapes' offsets along the turned normal.
  const L shift =
      dot(c.f.n, j.b.dp - j.a.dp) + load<L>(g.radius_b) * n_in_b.z + load<L>(g.radius_a) * n_in_a.z;
  [[maybe_unused]] L total_normal(0.0f);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    const Vec3<L> ra = load3<L>(p.r_a);
    const Vec3<L> rb = load3<L>(p.r_b);
    // The base and the turned arms' term are both about the distance between the centres
    // (a metre for stacked boxes) and cancel: summed first, the small shift keeps its bits.
    // (The order matters more than it should: a 10-box wall at 30 Hz holds to 0.8 mm summed
    // so, and crept 2.4 mm summed base + shift + arms: tests/contacts/pyramid_test.cpp.)
    const L separation = (load<L>(p.base_separation) + (dot(n_in_b, rb) - dot(n_in_a, ra))) + shift;
    const L accumulated = load<L>(p.normal_impulse);
    const L dp = contact_normal_impulse<L, kUseBias>(normal_speed(c, ra, rb), separation,
                                                     load<L>(p.normal_mass), accumulated, ctx, cc);
    const L next = accumulated + dp;
    store_lanes(p.normal_impulse, next);
    store_lanes(p.max_normal_impulse, max_lanes(load<L>(p.max_normal_impulse), next));
    if constexpr ((kSignature & kContactRolling) != 0) total_normal = total_normal + next;
    apply_normal(c.a, ra, L(0.0f) - dp);
    apply_normal(c.b, rb, dp);
  }
  if constexpr ((kSignature & kContactFriction) != 0) {
    const L friction = load<L>(g.friction);
    const L speed1 = load<L>(g.tangent_speed[0]);
    const L speed2 = load<L>(g.tangent_speed[1]);
    for (int i = 0; i < g.points; ++i) {
      auto& p = g.point[i];
      const Vec3<L> ra = load3<L>(p.r_a);
      const Vec3<L> rb = load3<L>(p.r_b);
      L a1, a2, b1, b2;
      tangent_speeds(c.a, ra, a1, a2);
      tangent_speeds(c.b, rb, b1, b2);
      const L old1 = load<L>(p.tangent_impulse[0]);
      const L old2 = load<L>(p.tangent_impulse[1]);
      L new1 = fmadd(L(0.0f) - load<L>(p.tangent_mass[0]), (b1 - a1) - speed1, old1);
      L new2 = fmadd(L(0.0f) - load<L>(p.tangent_mass[1]), (b2 - a2) - speed2, old2);
      // The disk clamp: scale both back onto the circle of radius friction * normal impulse.
      const L cap = friction * load<L>(p.normal_impulse);
      const L length2 = fmadd(new1, new1, new2 * new2);
      const auto over = length2 > cap * cap;
      const L scale = select(over, cap / sqrt_lanes(select(over, length2, L(1.0f))), L(1.0f));
      new1 = new1 * scale;
      new2 = new2 * scale;
      store_lanes(p.tangent_impulse[0], new1);
      store_lanes(p.tangent_impulse[1], new2);
      const L d1 = new1 - old1;
      const L d2 = new2 - old2;
      apply_tangent(c.a, ra, L(0.0f) - d1, L(0.0f) - d2);
      apply_tangent(c.b, rb, d1, d2);
    }
  }
  if constexpr ((kSignature & kContactRolling) != 0) {
    const Mat3Sym<L> m = load_sym<L>(g.rolling_mass);
    const Vec3<L> old = load3<L>(g.rolling_impulse);
    Vec3<L> next = old - m * (c.b.w - c.a.w);
    const L cap = load<L>(g.rolling_resistance) * total_normal;
    const L length2 = dot(next, next);
    const auto over = length2 > cap * cap;
    next = select(over, cap / sqrt_lanes(select(over, length2, L(1.0f))), L(1.0f)) * next;
    store3<L>(g.rolling_impulse, next);
    const Vec3<L> change = next - old;
    c.a.w = c.a.w - c.a.inv_inertia * change;
    c.b.w = c.b.w + c.b.inv_inertia * change;
  }
  leave_contact(g, bodies, c);
}

// After the sub-steps: the normal speed of each point that closed faster than the threshold
// at the step start and touched during the step becomes -restitution times that speed.
template <class L>
SOFTSTEP_INLINE void restitute_contacts(ContactLanes<kWidth<L>>& g, const BodyArrays& bodies,
                                        const ContactContext& cc) {
  ContactBodies<L> c = enter_contact<L, ContactGather::Velocity>(g, bodies);
  const L restitution = load<L>(g.restitution);
  for (int i = 0; i < g.points; ++i) {
    auto& p = g.point[i];
    const Vec3<L> ra = load3<L>(p.r_a);
    const Vec3<L> rb = load3<L>(p.r_b);
    const L approach = load<L>(p.relative_velocity);
    const auto bounces = approach < L(0.0f - cc.restitution_threshold) &&
                         load<L>(p.max_normal_impulse) > L(0.0f) && restitution > L(0.0f);
    const L accumulated = load<L>(p.normal_impulse);
    const L vn = normal_speed(c, ra, rb);
    const L raw = (L(0.0f) - load<L>(p.normal_mass)) * fmadd(restitution, approach, vn);
    const L dp = select(bounces, max_lanes(accumulated + raw, L(0.0f)) - accumulated, L(0.0f));
    store_lanes(p.normal_impulse, accumulated + dp);
    apply_normal(c.a, ra, L(0.0f) - dp);
    apply_normal(c.b, rb, dp);
  }
  leave_contact(g, bodies, c);
}

}  // namespace softstep::simd
