// The swing-twist joint: validation, lanes, the swing and twist in double for readings
// (see swing_twist_joint.hpp and simd/swing_twist_joint_kernel.hpp).
#include "joints/swing_twist_joint.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "joints/frame_joints.hpp"
#include "joints/joint_api.hpp"
#include "state_hasher.hpp"

namespace softstep {

namespace {

constexpr double kPi = std::numbers::pi;

// Where the impulses sit in a slot's block.
constexpr int kSwingImpulse = 3;
constexpr int kTwistLowerImpulse = 4;
constexpr int kTwistUpperImpulse = 5;
constexpr int kSpringImpulse = 6;
constexpr int kMotorImpulse = 9;

// The split of the kernel's header, in double: the angles, how far outside the cone B's axis
// leans (rad, 0 inside) and the two rows' world axes.
struct SwingTwistPose {
  double swing = 0.0, twist = 0.0, cone_violation = 0.0;
  Eigen::Vector3d swing_axis = Eigen::Vector3d::Zero();  // pushes back into the cone
  Eigen::Vector3d twist_axis = Eigen::Vector3d::Zero();
};

// 1 / sin^2(half_angle / 2): the swing quaternion's bound, squared, inverted.
double cone_inverse_square(double half_angle) {
  const double s = std::sin(0.5 * half_angle);
  return 1.0 / (s * s);
}

SwingTwistPose swing_twist_pose(const SwingTwistJointDef& d, const WorldFrames& f) {
  SwingTwistPose p;
  const Quaternion q = f.a.conjugate() * f.b;
  const Eigen::Vector3d zb = q * Eigen::Vector3d::UnitZ();
  const double s = std::hypot(zb.x(), zb.y());
  p.swing = std::atan2(s, zb.z());
  p.twist = 2.0 * std::atan2(q.z(), q.w());
  if (p.twist > kPi) p.twist -= 2.0 * kPi;
  if (p.twist <= -kPi) p.twist += 2.0 * kPi;
  const Eigen::Vector3d z_a = f.a * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_b = f.b * Eigen::Vector3d::UnitZ();
  if (1.0 + zb.z() > double(simd::kTwistSingularGap)) p.twist_axis = (z_a + z_b) / (1.0 + zb.z());
  if (!d.cone.enabled) return p;
  // The kernel's swing row (its header), in double: C >= 0 inside, rad near the edge.
  const double inv_x = cone_inverse_square(d.cone.half_angle_y);
  const double inv_y = cone_inverse_square(d.cone.half_angle_x);
  const double big_f = (zb.y() * zb.y() * inv_x + zb.x() * zb.x() * inv_y) / (2.0 * (1.0 + zb.z()));
  const Eigen::Vector3d grad =
      Eigen::Vector3d(zb.x() * inv_y, zb.y() * inv_x, -big_f) / (1.0 + zb.z());
  const Eigen::Vector3d rate = zb.cross(grad);
  if (!std::isfinite(big_f) || !(rate.norm() > 1e-12)) {
    // No swing (no direction to push) or a swing of 180 degrees (outside any cone but pi).
    if (!std::isfinite(big_f)) {
      p.cone_violation =
          std::max(0.0, p.swing - std::min(d.cone.half_angle_x, d.cone.half_angle_y));
    }
    return p;
  }
  const double root_f = std::sqrt(big_f);
  p.cone_violation = std::max(0.0, -2.0 * root_f * (1.0 - root_f) / rate.norm());
  p.swing_axis = -(f.a * rate.normalized());
  return p;
}

Eigen::Vector3d impulse3(const float* impulse, int at) {
  return Eigen::Vector3d(impulse[at], impulse[at + 1], impulse[at + 2]);
}

}  // namespace

std::uint32_t SwingTwistKind::signature(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return (d.cone.enabled ? simd::kSwingCone : 0u) | (d.twist.enabled ? simd::kTwistLimit : 0u) |
         (d.spring.spring.is_free() ? 0u : simd::kSwingTwistSpring) |
         (d.motor.enabled ? simd::kSwingTwistMotor : 0u);
}

int SwingTwistKind::rows(std::size_t, std::uint32_t s) {
  return 3 + ((s & simd::kSwingCone) ? 1 : 0) + ((s & simd::kTwistLimit) ? 2 : 0) +
         ((s & simd::kSwingTwistSpring) ? 3 : 0) + ((s & simd::kSwingTwistMotor) ? 3 : 0);
}

PlanKernel SwingTwistKind::plan_kernel(std::size_t, std::uint32_t s) {
  PlanKernel k{};
  k.type = type;
  k.row = (s & simd::kSwingTwistSpring) ? SpringRow::Soft : SpringRow::Rigid;
  k.parts = "point";
  if (s & simd::kSwingCone) k.parts += " + cone";
  if (s & simd::kTwistLimit) k.parts += " + twist limits";
  if (s & simd::kSwingTwistSpring) k.parts += " + spring";
  if (s & simd::kSwingTwistMotor) k.parts += " + friction";
  return k;
}

JointEffects SwingTwistKind::effects(const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  return {!d.spring.spring.is_free(), d.cone.enabled || d.twist.enabled, d.motor.enabled};
}

double SwingTwistKind::tension(const JointSlot&, const float* impulse) {
  return double(Eigen::Vector3f(impulse[0], impulse[1], impulse[2]).norm());
}

template <int W>
void SwingTwistKind::fill_lane(Group<W>& g, int lane, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  // A turn about x leans the axis towards y: its bound is half_angle_y (and the other way).
  const auto inverse_square = [&](double a) {
    return d.cone.enabled ? static_cast<float>(cone_inverse_square(a)) : 0.0f;
  };
  g.inv_cone_x_sq[lane] = inverse_square(d.cone.half_angle_y);
  g.inv_cone_y_sq[lane] = inverse_square(d.cone.half_angle_x);
  g.twist_lower[lane] = static_cast<float>(d.twist.lower);
  g.twist_upper[lane] = static_cast<float>(d.twist.upper);
  g.motor_max[lane] = static_cast<float>(d.motor.max_torque);
  fill_spring_lanes(g.spring, lane, d.spring.spring);
  for (int k = 0; k < 3; ++k) {
    g.point_impulse[k][lane] = j.impulse[k];
    g.spring_impulse[k][lane] = j.impulse[kSpringImpulse + k];
    g.motor_impulse[k][lane] = j.impulse[kMotorImpulse + k];
  }
  g.swing_impulse[lane] = j.impulse[kSwingImpulse];
  g.twist_lower_impulse[lane] = j.impulse[kTwistLowerImpulse];
  g.twist_upper_impulse[lane] = j.impulse[kTwistUpperImpulse];
}

template <int W>
void SwingTwistKind::write_step_start(Group<W>& g, int lane, JointSlot& j,
                                      const BodySlots& bodies) {
  const Def& d = std::get<Def>(j.def);
  const WorldFrames f = world_frames(bodies[j.body_a], bodies[j.body_b], d.frame_a, d.frame_b);
  write_frame_lanes(g, lane, f);
  const Quaternion target = (f.a * d.spring.target).normalized();
  g.target_a[0][lane] = static_cast<float>(target.x());
  g.target_a[1][lane] = static_cast<float>(target.y());
  g.target_a[2][lane] = static_cast<float>(target.z());
  g.target_a[3][lane] = static_cast<float>(target.w());
}

template <int W>
void SwingTwistKind::read_impulses(const Group<W>& g, int lane, float* out) {
  for (int k = 0; k < 3; ++k) {
    out[k] = g.point_impulse[k][lane];
    out[kSpringImpulse + k] = g.spring_impulse[k][lane];
    out[kMotorImpulse + k] = g.motor_impulse[k][lane];
  }
  out[kSwingImpulse] = g.swing_impulse[lane];
  out[kTwistLowerImpulse] = g.twist_lower_impulse[lane];
  out[kTwistUpperImpulse] = g.twist_upper_impulse[lane];
}

template <int W>
void SwingTwistKind::clear_impulses(Group<W>& g) {
  for (auto* rows : {&g.point_impulse, &g.spring_impulse, &g.motor_impulse}) {
    for (auto& row : *rows) std::fill(std::begin(row), std::end(row), 0.0f);
  }
  for (float* row : {g.swing_impulse, g.twist_lower_impulse, g.twist_upper_impulse})
    std::fill(row, row + W, 0.0f);
}

JointSlot SwingTwistKind::make_slot(const World::Impl& w, std::string_view call, const Def& def) {
  Def stored = def;
  JointSlot j =
      checked_frame_ends(w, call, def_name, def.body_a, def.body_b, stored.frame_a, stored.frame_b);
  const std::string prefix(def_name);
  for (const auto& [name, value] : {std::pair{".cone.half_angle_x", def.cone.half_angle_x},
                                    {".cone.half_angle_y", def.cone.half_angle_y}}) {
    validation::finite(call, prefix + name, value);
    // The kernel's cone row scales by 1 / sin^2(half_angle / 2) in float: below kMinPositive
    // its products overflow near a 180-degree swing (the fuzzer: a 1e-45 rad cone gave NaN
    // bodies). A narrower cone is a fixed swing: a revolute or weld joint holds it.
    if (def.cone.enabled && !(value >= validation::kMinPositive && value <= kPi)) {
      validation::reject(
          call, prefix + name, validation::format(value),
          "must lie in [" + validation::format(validation::kMinPositive) + ", pi] (rad)");
    }
  }
  check_axis_limit(call, prefix + ".twist", def.twist);
  if (def.twist.enabled) {
    for (const auto& [name, value] :
         {std::pair{".twist.lower", def.twist.lower}, {".twist.upper", def.twist.upper}}) {
      if (std::abs(value) > kPi) {
        validation::reject(call, prefix + name, validation::format(value),
                           "must lie within [-pi, pi] (rad)");
      }
    }
  }
  validation::relative_spring(call, prefix + ".spring.spring", def.spring.spring);
  if (def.spring.spring.is_rigid()) {
    validation::reject(call, prefix + ".spring.spring.hertz", "inf",
                       "an orientation spring is soft or free (a weld joint holds rigidly)");
  }
  const Eigen::Vector4d target = def.spring.target.coeffs();
  validation::finite(call, prefix + ".spring.target", Eigen::Vector3d(target.head<3>()));
  validation::finite(call, prefix + ".spring.target.w", target.w());
  if (!(target.norm() > 1e-9) || target.norm() > validation::kMaxMagnitude) {
    validation::reject(call, prefix + ".spring.target", validation::format(Eigen::Vector3d(target.head<3>())),
                       "must be a quaternion of length in (1e-9, 1e9] (it is normalized)");
  }
  stored.spring.target = def.spring.target.normalized();
  check_motor(call, prefix + ".motor", 0.0, def.motor.max_torque, "max_torque");
  j.type = type;
  j.def = stored;
  return j;
}

SwingTwistJointDef SwingTwistKind::def_of(const World::Impl&, const JointSlot& j) {
  return std::get<Def>(j.def);
}

void SwingTwistKind::reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                             JointReading& r) {
  const Def& d = std::get<Def>(j.def);
  const WorldAnchors anchors = world_anchors(w, j);
  const SwingTwistPose p = swing_twist_pose(d, world_frames(w, j, d.frame_a, d.frame_b));
  r.impulse = impulse3(impulse, 0);
  r.limit_impulse = double(impulse[kTwistLowerImpulse]) - double(impulse[kTwistUpperImpulse]);
  r.spring_impulse = impulse3(impulse, kSpringImpulse).norm();
  r.motor_impulse = impulse3(impulse, kMotorImpulse).norm();
  r.angular_impulse = double(impulse[kSwingImpulse]) * p.swing_axis +
                      r.limit_impulse * p.twist_axis + impulse3(impulse, kSpringImpulse) +
                      impulse3(impulse, kMotorImpulse);
  r.error = (anchors.b - anchors.a).norm();
  double twist_violation = 0.0;
  if (d.twist.enabled) {
    twist_violation = std::max({0.0, d.twist.lower - p.twist, p.twist - d.twist.upper});
  }
  r.angular_error = std::max(p.cone_violation, twist_violation);
  r.position = p.twist;
  r.swing = p.swing;
}

void SwingTwistKind::hash(StateHasher& h, const JointSlot& j) {
  const Def& d = std::get<Def>(j.def);
  hash_frame(h, d.frame_a);
  hash_frame(h, d.frame_b);
  h.value(d.cone.enabled);
  h.value(d.cone.half_angle_x);
  h.value(d.cone.half_angle_y);
  h.value(d.twist.enabled);
  h.value(d.twist.lower);
  h.value(d.twist.upper);
  h.value(d.spring.spring.hertz);
  h.value(d.spring.spring.damping_ratio);
  h.matrix(Eigen::Vector4d(d.spring.target.coeffs()));
  h.value(d.motor.enabled);
  h.value(d.motor.max_torque);
}

SOFTSTEP_INSTANTIATE_KIND(SwingTwistKind)
SOFTSTEP_INSTANTIATE_STEP_START(SwingTwistKind)
SOFTSTEP_INSTANTIATE_JOINT_API(SwingTwistJointDef)

}  // namespace softstep
