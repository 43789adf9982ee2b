// Swing-twist joint (shoulders, hips, necks), composed of parts, solved in this order (the
// hardest rows last):
//   spring     3 soft angular rows towards a target orientation (angular lock, soft)
//   motor      3 angular rows driving w_B - w_A to zero, |accumulated| <= max torque * h
//   twist      lower and upper limit rows about the twist axis
//   swing      one limit row keeping B's twist axis inside A's (elliptical) cone
//   point      3 linear rows keeping the anchors together
//
// The split: q = frame_A^-1 frame_B = q_swing q_twist, q_twist about z, q_swing about an axis
// in the xy plane (it takes z_A to z_B the short way). So the swing is measured from z_B seen
// in A's frame alone, zb = axis_z(q): its angle 2 atan(|zb_xy| / (1 + zb_z)) and its direction
// do not depend on the twist; the twist is 2 atan2(q.z, q.w) (twist_angle_z).
//
// Twist row: d(twist)/dt = u . (w_B - w_A) with u = (z_A + z_B) / (1 + z_A . z_B), exact
// (differentiate 2 atan2(q.z, q.w) with q' = 1/2 w_rel q). |u| = 1 / cos(swing / 2) grows near
// a 180-degree swing, where the twist is undefined: the rows' effective mass falls as
// cos^2(swing / 2), so what they do to the bodies fades out, and past kTwistSingularGap they
// are off (impulse 0).
//
// Swing row (elliptical cone, half-angles a towards A's x, b towards A's y): the swing
// quaternion's (x, y) lies inside the ellipse F = (x / sin(b/2))^2 + (y / sin(a/2))^2 <= 1
// (exactly the cone of half-angle a towards x and b towards y, an ellipse between; a circle
// of half-angle a when a = b). F depends on zb alone, so dF/dt = (zb x grad F) . w_rel in A's
// frame, exact, and perpendicular to zb: a twist of B about its own axis never moves the row,
// the cone holds at its edge however large or fast the twist. C = (1 - sqrt F) / |rate of
// sqrt F| (rad: the edge's distance, linearized), along the unit axis of that rate.
#pragma once

#include "softstep/simd/frame_lanes.hpp"
#include "softstep/simd/parts/angular_parts.hpp"
#include "softstep/simd/parts/point_part.hpp"

namespace softstep::simd {

// Signature bits: which parts a swing-twist joint runs.
inline constexpr std::uint32_t kSwingCone = 1u;
inline constexpr std::uint32_t kTwistLimit = 2u;
inline constexpr std::uint32_t kSwingTwistSpring = 4u;
inline constexpr std::uint32_t kSwingTwistMotor = 8u;

// 1 + z_A . z_B = 2 cos^2(swing / 2) below which the twist rows are off (swing > 177.4 deg).
inline constexpr float kTwistSingularGap = 1.0e-3f;

template <int W>
struct alignas(kLaneAlign<W>) SwingTwistJointGroup : FrameLanes<W> {
  float target_a[4][W];     // frame_A turned by the spring's target, world, step start
  float inv_cone_x_sq[W];   // 1 / sin^2(b/2): b, the largest swing towards y (about x)
  float inv_cone_y_sq[W];   // 1 / sin^2(a/2): a, the largest swing towards x (about y)
  float twist_lower[W];     // rad, in [-pi, pi]
  float twist_upper[W];
  float motor_max[W];       // N m
  float motor_max_impulse[W];  // prepared: motor_max * h
  SoftRowLanes<W> spring;
  float point_impulse[3][W];
  float swing_impulse[W];
  float twist_lower_impulse[W];
  float twist_upper_impulse[W];
  float spring_impulse[3][W];
  float motor_impulse[3][W];
};

namespace detail {
template <class L>
struct SwingTwistNow {
  Vec3<L> swing_axis;  // world, unit, the push back into the cone: dC/dt = axis . (w_B - w_A)
  L swing_gap;         // C >= 0 inside the cone, rad
  Vec3<L> twist_axis;  // world, (z_A + z_B) / (1 + z_A . z_B), zero near the singularity
  L twist;             // rad, (-pi, pi]
};

// 1/x where x > floor, else `otherwise`.
template <class L>
SOFTSTEP_INLINE L inverse_above(const L& x, float floor, const L& otherwise) {
  const auto ok = x > L(floor);
  return select(ok, L(1.0f) / select(ok, x, L(1.0f)), otherwise);
}

template <class L>
SOFTSTEP_INLINE SwingTwistNow<L> swing_twist_now(const SwingTwistJointGroup<kWidth<L>>& g,
                                                 const JointBodies<L>& j) {
  const Frames<L> f = current_frames(g, j);
  const Quat<L> q = multiply(conjugate(f.a), f.b);
  const Vec3<L> zb = axis_z(q);  // B's twist axis in A's frame
  const L one_plus_c = L(1.0f) + zb.z;
  // F = (x_s / sin(b/2))^2 + (y_s / sin(a/2))^2 of the swing quaternion, from zb:
  // q_swing = (-zb.y, zb.x, 0, 1 + zb.z) / sqrt(2 (1 + zb.z)).
  const L inv_two_one_plus_c = inverse_above(L(2.0f) * one_plus_c, 0.0f, L(0.0f));
  const L wx = zb.y * load<L>(g.inv_cone_x_sq);  // the swing's x part leans towards -y
  const L wy = zb.x * load<L>(g.inv_cone_y_sq);
  const L big_f = fmadd(zb.y, wx, zb.x * wy) * inv_two_one_plus_c;
  // grad F (zb) = ((wy, wx, 0) - F (0, 0, 1)) / (1 + zb.z); dF/dt = (zb x grad F) . w_rel.
  const L two = L(2.0f) * inv_two_one_plus_c;
  const Vec3<L> grad{wy * two, wx * two, (L(0.0f) - big_f) * two};
  const Vec3<L> g_rate = cross(zb, grad);
  const L root_f = sqrt_lanes(big_f);
  // C = (1 - sqrt F) / |d sqrt F / d angle| = 2 sqrt F (1 - sqrt F) / |G|, rad near the edge.
  const L inv_g = inverse_above(sqrt_lanes(dot(g_rate, g_rate)), 1.0e-12f, L(0.0f));
  const L gap = L(2.0f) * root_f * (L(1.0f) - root_f) * inv_g;
  const Vec3<L> push = -(inv_g * rotate(f.a, g_rate));
  const Vec3<L> z_a = axis_z(f.a);
  const Vec3<L> z_b = axis_z(f.b);
  const Vec3<L> twist_axis = inverse_above(one_plus_c, kTwistSingularGap, L(0.0f)) * (z_a + z_b);
  return {push, gap, twist_axis, twist_angle_z(q)};
}

// One one-sided angular row: C = gap >= 0 with dC/dt = sign * axis . (w_B - w_A).
template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_angular_limit(JointBodies<L>& j, const Vec3<L>& axis, const L& gap,
                                         float (&impulse)[kWidth<L>], const SubstepContext& ctx) {
  const AngularAxis<L> row = angular_axis(j, axis);
  const L accumulated = load<L>(impulse);
  const L dp = limit_row_impulse<L, kUseBias>(row.cdot, gap, row.k, row.m_eff, accumulated,
                                              ctx, ctx.limit);
  store_lanes(impulse, accumulated + dp);
  apply_angular_impulse(j, dp * axis);
}

// The friction-like motor: 3 rows w_B - w_A -> 0 as one block, the accumulated angular
// impulse capped in length (a friction disk, in 3D a ball) by max torque * h.
template <class L>
SOFTSTEP_INLINE void solve_angular_friction(JointBodies<L>& j, float (&impulse)[3][kWidth<L>],
                                            const L& max_impulse) {
  const Mat3Sym<L> k_inv = inverse_or_zero(j.a.inv_inertia + j.b.inv_inertia);
  const Vec3<L> accumulated = load3<L>(impulse);
  const Vec3<L> wanted = accumulated - k_inv * relative_angular_velocity(j);
  const L length = sqrt_lanes(dot(wanted, wanted));
  const L scale = select(length > max_impulse, max_impulse * inverse_above(length, 0.0f, L(0.0f)),
                         L(1.0f));
  const Vec3<L> next = scale * wanted;
  store3<L>(impulse, next);
  apply_angular_impulse(j, next - accumulated);
}
}  // namespace detail

template <class L>
SOFTSTEP_INLINE void prepare_swing_twist_joints(SwingTwistJointGroup<kWidth<L>>& g,
                                                const SubstepContext& ctx,
                                                std::uint32_t signature) {
  if (signature & kSwingTwistSpring)
    prepare_row_coefficients<L, JointFeatures{RowKind::Soft, false, false}>(g.spring, ctx);
  if (signature & kSwingTwistMotor)
    store_lanes(g.motor_max_impulse, load<L>(g.motor_max) * L(ctx.h));
}

template <class L>
SOFTSTEP_INLINE void warm_start_swing_twist_joints(SwingTwistJointGroup<kWidth<L>>& g,
                                                   const BodyArrays& bodies,
                                                   std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  Vec3<L> torque = (signature & kSwingTwistSpring) ? load3<L>(g.spring_impulse)
                                                   : Vec3<L>{L(0.0f), L(0.0f), L(0.0f)};
  if (signature & kSwingTwistMotor) torque = torque + load3<L>(g.motor_impulse);
  if (signature & (kSwingCone | kTwistLimit)) {
    const detail::SwingTwistNow<L> s = detail::swing_twist_now<L>(g, j);
    if (signature & kTwistLimit) {
      const L twist = load<L>(g.twist_lower_impulse) - load<L>(g.twist_upper_impulse);
      torque = mul_add(twist, s.twist_axis, torque);
    }
    if (signature & kSwingCone) torque = mul_add(load<L>(g.swing_impulse), s.swing_axis, torque);
  }
  apply_angular_impulse(j, torque);
  warm_start_point(j, g.point_impulse);
  scatter_joint(g, bodies, j);
}

template <class L, bool kUseBias>
SOFTSTEP_INLINE void solve_swing_twist_joints(SwingTwistJointGroup<kWidth<L>>& g,
                                              const BodyArrays& bodies, const SubstepContext& ctx,
                                              std::uint32_t signature) {
  JointBodies<L> j = gather_joint<L>(g, bodies);
  if constexpr (kUseBias) {
    if (signature & kSwingTwistSpring) {
      const Quat<L> target = multiply(j.a.dq, load_quat<L>(g.target_a));
      const Quat<L> frame_b = multiply(j.b.dq, load_quat<L>(g.frame_b));
      solve_angular_lock3<L, true, RowKind::Soft>(j, rotation_error(target, frame_b),
                                                  g.spring_impulse, load_coefficients<L>(g.spring));
    }
  }
  if (signature & kSwingTwistMotor)
    detail::solve_angular_friction(j, g.motor_impulse, load<L>(g.motor_max_impulse));
  if (signature & (kSwingCone | kTwistLimit)) {
    const detail::SwingTwistNow<L> s = detail::swing_twist_now<L>(g, j);
    if (signature & kTwistLimit) {
      detail::solve_angular_limit<L, kUseBias>(j, s.twist_axis, s.twist - load<L>(g.twist_lower),
                                               g.twist_lower_impulse, ctx);
      detail::solve_angular_limit<L, kUseBias>(j, -s.twist_axis,
                                               load<L>(g.twist_upper) - s.twist,
                                               g.twist_upper_impulse, ctx);
    }
    if (signature & kSwingCone) {
      detail::solve_angular_limit<L, kUseBias>(j, s.swing_axis, s.swing_gap, g.swing_impulse, ctx);
    }
  }
  solve_point<L, kUseBias, RowKind::Rigid>(j, g.point_impulse, rigid_coefficients<L>(ctx));
  scatter_joint(g, bodies, j);
}

}  // namespace softstep::simd
