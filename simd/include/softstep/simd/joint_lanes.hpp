// What every two-body joint kernel shares: the lanes that name the bodies, the anchors and
// the spring, the per-step row coefficients, and the gather of both bodies with the anchors
// turned to where the bodies are now.
#pragma once

#include <cstdint>

#include "softstep/simd/step_context.hpp"

namespace softstep::simd {

// Marks a padding lane in JointLanes::id.
inline constexpr std::uint32_t kPaddingLane = 0xFFFFFFFFu;

// What the spring row of every lane of a group is. Any: each lane says (hertz +inf = rigid,
// 0 = free, else soft) and the kernel switches per lane; the others are the same for all lanes
// of the group, so the kernel is compiled with only that case's terms.
enum class RowKind : std::uint8_t { Any, Rigid, Soft, Free };

// The features a kernel is compiled for: a template parameter, so one kernel source gives a
// variant per signature and no lane evaluates a term or a branch its group does not need.
// The default is the general kernel, which handles every lane by its values (a padding lane,
// a disabled limit, a free spring: all by per-lane switches).
struct JointFeatures {
  RowKind row = RowKind::Any;
  bool lower = true;  // distance joints: the min-length row (per-lane enable in Any)
  bool upper = true;  // distance joints: the max-length row
  constexpr bool operator==(const JointFeatures&) const = default;
};
inline constexpr JointFeatures kGeneralKernel{};

// The lanes every two-body constraint starts with: who it is, its bodies, and its anchors.
template <int W>
struct alignas(kLaneAlign<W>) AnchorLanes {
  std::uint32_t id[W];  // the caller's id for the constraint in this lane, kPaddingLane if none
  std::int32_t body_a[W];
  std::int32_t body_b[W];
  // Written before prepare each step (core's anchor pass), world frame, at the step start:
  float r_a[3][W];           // anchor A - centre of mass A, m
  float r_b[3][W];           // anchor B - centre of mass B, m
  float center_delta[3][W];  // centre B - centre A, m (from double positions: precise far out)
};

// A spring's frequency per lane and the row coefficients prepared from it once per step
// (prepare_row_coefficients): what a row that may be rigid, soft or free per lane solves with.
template <int W>
struct alignas(kLaneAlign<W>) SoftRowLanes {
  // Spring, constant while the joint lives: hertz +inf = rigid, 0 = free.
  float hertz[W];
  float zeta[W];
  // Prepared once per step (prepare_row_coefficients):
  float bias_rate[W];
  float mass_scale[W];
  float impulse_scale[W];
  float feedback[W];     // 1/a: gamma' = feedback * K (see softness.hpp)
  float max_bias[W];     // m/s, +inf for springs
  float relax_scale[W];  // 1 for rigid rows, 0 for springs (springs are not relaxed)
};

// The ball and distance joints: anchors and one spring for all their rows.
template <int W>
struct alignas(kLaneAlign<W>) JointLanes : AnchorLanes<W>, SoftRowLanes<W> {};

template <class L, JointFeatures F = kGeneralKernel, int W>
SOFTSTEP_INLINE void prepare_row_coefficients(SoftRowLanes<W>& g, const SubstepContext& ctx) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if constexpr (F.row == RowKind::Rigid) {
    store_lanes(g.bias_rate, L(ctx.rigid.bias_rate));
    store_lanes(g.mass_scale, L(ctx.rigid.mass_scale));
    store_lanes(g.impulse_scale, L(ctx.rigid.impulse_scale));
    store_lanes(g.feedback, L(ctx.rigid.feedback));
    store_lanes(g.max_bias, L(ctx.max_correction_speed));
    store_lanes(g.relax_scale, L(1.0f));
    return;
  } else if constexpr (F.row != RowKind::Any) {
    const Softness<L> spring = make_softness(load<L>(g.hertz), load<L>(g.zeta), ctx.h);
    store_lanes(g.bias_rate, spring.bias_rate);
    store_lanes(g.mass_scale, spring.mass_scale);
    store_lanes(g.impulse_scale, spring.impulse_scale);
    store_lanes(g.feedback, spring.feedback);
    store_lanes(g.max_bias, L(kInf));
    store_lanes(g.relax_scale, L(0.0f));
    return;
  }
  const L hertz = load<L>(g.hertz);
  const auto rigid = hertz == L(kRigidHertz);
  const Softness<L> spring = make_softness(select(rigid, L(0.0f), hertz), load<L>(g.zeta), ctx.h);
  store_lanes(g.bias_rate, select(rigid, L(ctx.rigid.bias_rate), spring.bias_rate));
  store_lanes(g.mass_scale, select(rigid, L(ctx.rigid.mass_scale), spring.mass_scale));
  store_lanes(g.impulse_scale, select(rigid, L(ctx.rigid.impulse_scale), spring.impulse_scale));
  store_lanes(g.feedback, select(rigid, L(ctx.rigid.feedback), spring.feedback));
  store_lanes(g.max_bias, select(rigid, L(ctx.max_correction_speed), L(kInf)));
  store_lanes(g.relax_scale, select(rigid, L(1.0f), L(0.0f)));
}

template <class L>
SOFTSTEP_INLINE Vec3<L> load3(const float (&a)[3][kWidth<L>]) {
  return {load<L>(a[0]), load<L>(a[1]), load<L>(a[2])};
}
template <class L>
SOFTSTEP_INLINE void store3(float (&a)[3][kWidth<L>], const Vec3<L>& v) {
  store_lanes(a[0], v.x);
  store_lanes(a[1], v.y);
  store_lanes(a[2], v.z);
}

// Both bodies of W joints as they are now, with the anchors rotated by each body's rotation
// since the step start and the anchor separation (anchor B - anchor A).
template <class L>
struct JointBodies {
  BodyLanes<L> a, b;
  Vec3<L> r_a, r_b;
  Vec3<L> separation;
};

template <class L>
SOFTSTEP_INLINE JointBodies<L> gather_joint(const AnchorLanes<kWidth<L>>& g,
                                            const BodyArrays& bodies) {
  JointBodies<L> j;  // filled in place (gather_body_into says why)
  gather_body_into(j.a, bodies.velocity, bodies.delta, bodies.mass, g.body_a);
  gather_body_into(j.b, bodies.velocity, bodies.delta, bodies.mass, g.body_b);
  j.r_a = rotate(j.a.dq, load3<L>(g.r_a));
  j.r_b = rotate(j.b.dq, load3<L>(g.r_b));
  j.separation = load3<L>(g.center_delta) + (j.b.dp - j.a.dp) + (j.r_b - j.r_a);
  return j;
}

// Writes both bodies' velocities back: any lane group naming body_a and body_b (every joint
// kind's lanes, and the contacts').
template <class L, class Lanes>
SOFTSTEP_INLINE void scatter_joint(const Lanes& g, const BodyArrays& bodies,
                                   const JointBodies<L>& j) {
  scatter_velocity(bodies.velocity, g.body_a, j.a);
  scatter_velocity(bodies.velocity, g.body_b, j.b);
}

// Impulse p on B at arm_b from its centre, -p on A at arm_a from its centre.
template <class L>
SOFTSTEP_INLINE void apply_impulse_at(JointBodies<L>& j, const Vec3<L>& p, const Vec3<L>& arm_a,
                                      const Vec3<L>& arm_b) {
  j.a.v = mul_add(L(0.0f) - j.a.inv_mass, p, j.a.v);
  j.a.w = j.a.w - j.a.inv_inertia * cross(arm_a, p);
  j.b.v = mul_add(j.b.inv_mass, p, j.b.v);
  j.b.w = j.b.w + j.b.inv_inertia * cross(arm_b, p);
}

// Impulse p on B at its anchor, -p on A at its anchor.
template <class L>
SOFTSTEP_INLINE void apply_impulse(JointBodies<L>& j, const Vec3<L>& p) {
  apply_impulse_at(j, p, j.r_a, j.r_b);
}

// Angular impulse t on B, -t on A (N m s): what an angular row applies.
template <class L>
SOFTSTEP_INLINE void apply_angular_impulse(JointBodies<L>& j, const Vec3<L>& t) {
  j.a.w = j.a.w - j.a.inv_inertia * t;
  j.b.w = j.b.w + j.b.inv_inertia * t;
}

// Velocity of anchor B relative to anchor A: J v of the three point rows.
template <class L>
SOFTSTEP_INLINE Vec3<L> relative_velocity(const JointBodies<L>& j) {
  return (j.b.v + cross(j.b.w, j.r_b)) - (j.a.v + cross(j.a.w, j.r_a));
}

template <class L>
SOFTSTEP_INLINE L clamp_lanes(const L& v, const L& bound) {
  return min_lanes(max_lanes(v, L(0.0f) - bound), bound);
}

// The bias a rigid row solves with, given bias = bias_rate * C and the velocity its
// accumulated impulse feeds back, gamma' P. What is bounded by max_bias is their sum: the
// speed at which the row asks to close its error. A loaded row at rest has the two in
// balance (bias_rate C + gamma' P = 0), so its load is untouched by the bound however large;
// a row created far apart (P = 0) closes at max_bias instead of launching its bodies.
// Bounding the bias alone made a chain under a heavy load sink without end: the stretch the
// load needs asked for more than max_bias.
// Springs (bound = +inf) keep their bias untouched, so a spring stays exactly the
// implicit-Euler spring (adding and removing gamma' P would round).
// A group known to be rigid takes the bounded side without the per-lane test (springs do
// not call it: their bias is never bounded).
template <class L, RowKind kRow = RowKind::Any>
SOFTSTEP_INLINE L bounded_bias(const L& bias, const L& feedback_velocity, const L& bound) {
  if constexpr (kRow == RowKind::Rigid) {
    return clamp_lanes(bias + feedback_velocity, bound) - feedback_velocity;
  } else {
    return select(bound == L(std::numeric_limits<float>::infinity()), bias,
                  clamp_lanes(bias + feedback_velocity, bound) - feedback_velocity);
  }
}

}  // namespace softstep::simd
