// Drives the public API with random sequences of operations and values, including NaN, inf,
// huge and tiny ones, and checks the promises of the API:
//   - a rejected call (InvalidArgument) leaves the world exactly as it was (state_hash);
//   - a world built only from accepted calls never holds a non-finite value after a step;
//   - nothing crashes and no sanitizer reports (the build adds address + undefined).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "softstep/softstep.hpp"

namespace {

using softstep::BodyId;
using softstep::JointId;

double value(FuzzedDataProvider& in) {
  static constexpr double kSpecial[] = {
      0.0,  -0.0,  1.0,    -1.0,     0.25,      1e-300, -1e-300, 1e-30, 1e-9, 1e6, 1e12, 1e18,
      1e19, 1e300, -1e300, INFINITY, -INFINITY, NAN,    3.5e38,  1e-45, 60.0, 0.5, 2.0,  1e30};
  if (in.ConsumeBool())
    return kSpecial[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kSpecial) - 1)];
  return in.ConsumeFloatingPointInRange<double>(-100.0, 100.0);
}

Eigen::Vector3d vec(FuzzedDataProvider& in) {
  return {value(in), value(in), value(in)};
}

softstep::Spring spring(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 4)) {
    case 0:
      return softstep::Spring::rigid();
    case 1:
      return softstep::Spring::free();
    case 2:
      return softstep::Spring::absolute(value(in), value(in));  // taken by one-row springs only
    default:
      return softstep::Spring::soft(value(in), value(in));
  }
}

template <class Id>
Id pick(FuzzedDataProvider& in, const std::vector<Id>& ids) {
  if (ids.empty() || in.ConsumeIntegralInRange<int>(0, 9) == 0) {
    return Id{in.ConsumeIntegral<std::uint32_t>() % 64, in.ConsumeIntegral<std::uint32_t>() % 3};
  }
  return ids[in.ConsumeIntegralInRange<std::size_t>(0, ids.size() - 1)];
}

// A joint frame: unit or random axes, a reference perpendicular, random or (invalid)
// parallel to the axis, and a zero or random anchor.
softstep::JointFrame frame(FuzzedDataProvider& in) {
  static const Eigen::Vector3d kAxes[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                          Eigen::Vector3d::UnitZ()};
  softstep::JointFrame f;
  f.local_anchor = in.ConsumeBool() ? Eigen::Vector3d::Zero() : vec(in);
  const int axis = in.ConsumeIntegralInRange<int>(0, 3);
  f.local_axis = axis < 3 ? kAxes[axis] : vec(in);
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
      f.local_reference = kAxes[(axis + 1) % 3];
      break;
    case 1:
      f.local_reference = vec(in);
      break;
    default:
      f.local_reference = f.local_axis * value(in);  // parallel: rejected
      break;
  }
  return f;
}

// SOFTSTEP_FUZZ_VERBOSE=1 prints every accepted call's kind and the bodies after each step,
// for replaying a crash input by hand.
bool verbose() {
  static const bool on = std::getenv("SOFTSTEP_FUZZ_VERBOSE") != nullptr;
  return on;
}

void print_frame(const char* name, const softstep::JointFrame& f) {
  std::fprintf(
      stderr,
      "  %s anchor (%.17g %.17g %.17g) axis (%.17g %.17g %.17g) reference (%.17g %.17g %.17g)\n",
      name, f.local_anchor.x(), f.local_anchor.y(), f.local_anchor.z(), f.local_axis.x(),
      f.local_axis.y(), f.local_axis.z(), f.local_reference.x(), f.local_reference.y(),
      f.local_reference.z());
}

void print_axis_controls(const softstep::AxisLimit& limit, bool motor_on, double motor_speed,
                         double motor_max, const softstep::AxisSpring& spring) {
  if (!verbose()) return;
  std::fprintf(stderr,
               "  limit %d %.17g %.17g motor %d %.17g %.17g spring %.17g Hz %.17g target %.17g\n",
               int(limit.enabled), limit.lower, limit.upper, int(motor_on), motor_speed, motor_max,
               spring.spring.hertz, spring.spring.damping_ratio, spring.target);
}

// Both frames: from frames_at (valid when the inputs are) or drawn one by one.
void frames(FuzzedDataProvider& in, softstep::World& w, BodyId a, BodyId b,
            softstep::JointFrame& fa, softstep::JointFrame& fb) {
  if (in.ConsumeBool()) {
    const softstep::JointFrames f = softstep::frames_at(w, a, b, vec(in), vec(in));
    fa = f.a;
    fb = f.b;
  } else {
    fa = frame(in);
    fb = frame(in);
  }
  if (verbose()) {
    print_frame("frame_a", fa);
    print_frame("frame_b", fb);
  }
}

softstep::AxisLimit limit(FuzzedDataProvider& in) {
  softstep::AxisLimit l;
  l.enabled = in.ConsumeBool();
  l.lower = value(in);
  l.upper = in.ConsumeBool() ? std::abs(value(in)) : value(in);  // sometimes below lower
  return l;
}

softstep::AxisSpring axis_spring(FuzzedDataProvider& in) {
  return {spring(in), in.ConsumeBool() ? 0.0 : value(in)};  // rigid: rejected
}

template <class Motor>
Motor motor(FuzzedDataProvider& in) {
  Motor m;
  m.enabled = in.ConsumeBool();
  m.speed = value(in);
  if constexpr (requires { m.max_torque; }) {
    m.max_torque = value(in);  // negative: rejected
  } else {
    m.max_force = value(in);
  }
  return m;
}

// The swing-twist joint's limits, spring and friction: random, sometimes out of range.
void swing_twist_parts(FuzzedDataProvider& in, softstep::SwingTwistJointDef& d) {
  d.cone.enabled = in.ConsumeBool();
  d.cone.half_angle_x = value(in);  // <= 0 or > pi: rejected
  d.cone.half_angle_y = in.ConsumeBool() ? d.cone.half_angle_x : value(in);
  d.twist = limit(in);
  d.spring.spring = spring(in);
  d.spring.target = softstep::Quaternion(value(in), value(in), value(in), value(in));
  d.motor.enabled = in.ConsumeBool();
  d.motor.max_torque = value(in);
  if (verbose()) {
    const softstep::Quaternion& t = d.spring.target;
    std::fprintf(stderr,
                 "  cone %d %.17g %.17g twist %d %.17g %.17g spring %.17g Hz %.17g target "
                 "(%.17g %.17g %.17g %.17g) motor %d %.17g\n",
                 int(d.cone.enabled), d.cone.half_angle_x, d.cone.half_angle_y,
                 int(d.twist.enabled), d.twist.lower, d.twist.upper, d.spring.spring.hertz,
                 d.spring.spring.damping_ratio, t.x(), t.y(), t.z(), t.w(), int(d.motor.enabled),
                 d.motor.max_torque);
  }
}

// Changes one part of a revolute or prismatic definition (or a weld's springs or frames).
template <class Def>
void mutate(FuzzedDataProvider& in, Def& d) {
  switch (in.ConsumeIntegralInRange<int>(0, 4)) {
    case 0:
      d.frame_a = frame(in);
      break;
    case 1:
      d.frame_b = frame(in);
      break;
    case 2:
      if constexpr (requires { d.limit; }) d.limit = limit(in);
      if constexpr (requires { d.angular; }) d.angular = spring(in);
      break;
    case 3:
      if constexpr (requires { d.motor; }) d.motor = motor<decltype(d.motor)>(in);
      if constexpr (requires { d.linear; }) d.linear = spring(in);
      break;
    default:
      if constexpr (requires { d.spring; }) d.spring = axis_spring(in);
      if constexpr (requires { d.steering; }) {
        d.steering = value(in);
        d.sprung_mass = value(in);
      }
      if constexpr (requires { d.max_force; }) {
        d.max_force = value(in);
        d.max_torque = value(in);
      }
      break;
  }
}

// Up to four manifolds between random bodies, each field valid or not: a normal along y, a
// random unit or non-unit one; 0 to 5 points; separations mostly within a few centimetres.
std::vector<softstep::ContactManifold> manifolds(FuzzedDataProvider& in,
                                                 const std::vector<BodyId>& bodies) {
  std::vector<softstep::ContactManifold> list(in.ConsumeIntegralInRange<std::size_t>(1, 4));
  for (softstep::ContactManifold& m : list) {
    m.body_a = pick(in, bodies);
    m.body_b = pick(in, bodies);
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
      case 0:
        break;  // +y
      case 1:
        m.normal = vec(in).normalized();
        break;
      default:
        m.normal = vec(in);
        break;
    }
    m.point_count = in.ConsumeIntegralInRange<int>(0, softstep::kMaxContactPoints + 1);
    for (softstep::ContactPoint& p : m.points) {
      if (in.ConsumeBool()) p.anchor_a = vec(in);
      if (in.ConsumeBool()) p.anchor_b = vec(in);
      p.separation =
          in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(-0.1, 0.05) : value(in);
      p.feature_id = in.ConsumeIntegral<std::uint8_t>();
    }
    if (in.ConsumeBool()) m.friction = value(in);
    if (in.ConsumeBool()) m.restitution = value(in);
    if (in.ConsumeBool()) m.rolling_resistance = value(in);
    if (in.ConsumeBool()) m.tangent_speed = {value(in), value(in)};
    m.key = in.ConsumeIntegral<std::uint8_t>();
    if (in.ConsumeBool()) m.radius_a = value(in);
    if (in.ConsumeBool()) m.radius_b = value(in);
    if (verbose()) {
      std::fprintf(stderr,
                   "  manifold %u-%u normal (%.17g %.17g %.17g) points %d friction %.17g "
                   "restitution %.17g rolling %.17g tangent speed (%.17g %.17g) radii %.17g "
                   "%.17g\n",
                   m.body_a.index, m.body_b.index, m.normal.x(), m.normal.y(), m.normal.z(),
                   m.point_count, m.friction, m.restitution, m.rolling_resistance,
                   m.tangent_speed.x(), m.tangent_speed.y(), m.radius_a, m.radius_b);
      for (int i = 0; i < std::min(m.point_count, softstep::kMaxContactPoints); ++i) {
        const softstep::ContactPoint& p = m.points[static_cast<std::size_t>(i)];
        std::fprintf(stderr,
                     "    point a (%.17g %.17g %.17g) b (%.17g %.17g %.17g) separation %.17g "
                     "feature %u\n",
                     p.anchor_a.x(), p.anchor_a.y(), p.anchor_a.z(), p.anchor_b.x(), p.anchor_b.y(),
                     p.anchor_b.z(), p.separation, p.feature_id);
      }
    }
  }
  return list;
}

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "world_fuzzer: %s\n", what);
  __builtin_trap();
}

void check_finite(const softstep::World& w, const std::vector<BodyId>& bodies) {
  for (BodyId b : bodies) {
    if (!w.is_valid(b)) continue;
    const softstep::BodyState s = w.body(b);
    if (!s.position.allFinite() || !s.linear_velocity.allFinite() ||
        !s.angular_velocity.allFinite() || !s.orientation.coeffs().allFinite()) {
      fail("a world built from accepted calls holds a non-finite body after a step");
    }
  }
}

}  // namespace

void dump(const softstep::World& w, const std::vector<BodyId>& bodies) {
  for (BodyId b : bodies) {
    if (!w.is_valid(b)) continue;
    const softstep::BodyState s = w.body(b);
    std::fprintf(
        stderr,
        "  body %u type %d m %g p (%.17g %.17g %.17g) q (%.17g %.17g %.17g %.17g) v (%.17g "
        "%.17g %.17g) w (%.17g %.17g %.17g) I00 %g\n",
        b.index, static_cast<int>(s.type), s.mass, s.position.x(), s.position.y(), s.position.z(),
        s.orientation.x(), s.orientation.y(), s.orientation.z(), s.orientation.w(),
        s.linear_velocity.x(), s.linear_velocity.y(), s.linear_velocity.z(), s.angular_velocity.x(),
        s.angular_velocity.y(), s.angular_velocity.z(), s.inertia(0, 0));
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  softstep::WorldSettings settings;
  settings.substeps = in.ConsumeIntegralInRange<int>(1, 4);
  softstep::World world(settings);
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
  for (int op = 0; op < 48 && in.remaining_bytes() > 0; ++op) {
    const std::uint64_t before = world.state_hash();
    try {
      switch (in.ConsumeIntegralInRange<int>(0, 11)) {
        case 0:
        case 1: {
          if (bodies.size() >= 24) break;
          softstep::BodyDef d;
          d.type = static_cast<softstep::BodyType>(in.ConsumeIntegralInRange<int>(0, 3));
          d.position = vec(in);
          d.orientation = softstep::Quaternion(value(in), value(in), value(in), value(in));
          if (in.ConsumeBool()) d.orientation = softstep::Quaternion::Identity();
          d.linear_velocity = vec(in);
          d.angular_velocity = vec(in);
          d.mass = value(in);
          if (in.ConsumeBool()) {
            d.inertia = softstep::solid_sphere_inertia(std::abs(d.mass), std::abs(value(in)));
          } else {
            for (int k = 0; k < 9; ++k) d.inertia(k / 3, k % 3) = value(in);
          }
          d.gravity_scale = value(in);
          d.linear_damping = in.ConsumeBool() ? 0.0 : value(in);
          bodies.push_back(world.create_body(d));
          if (verbose()) {
            std::fprintf(stderr, "body %u type %d m %.17g gravity_scale %g inertia",
                         bodies.back().index, static_cast<int>(d.type), d.mass, d.gravity_scale);
            for (int k = 0; k < 9; ++k) std::fprintf(stderr, " %.17g", d.inertia(k / 3, k % 3));
            std::fprintf(stderr, "\n");
          }
          break;
        }
        case 2:
          world.destroy_body(pick(in, bodies));
          break;
        case 3:
        case 4: {
          if (joints.size() >= 48) break;
          if (in.ConsumeBool()) {
            softstep::BallJointDef j;
            j.body_a = pick(in, bodies);
            j.body_b = pick(in, bodies);
            j.local_anchor_a = in.ConsumeBool() ? Eigen::Vector3d::Zero() : vec(in);
            j.local_anchor_b = in.ConsumeBool() ? Eigen::Vector3d::Zero() : vec(in);
            j.spring = spring(in);
            joints.push_back(world.create_ball_joint(j));
            if (verbose()) {
              std::fprintf(stderr, "ball %u-%u ra (%g %g %g) rb (%g %g %g) hertz %g zeta %g\n",
                           j.body_a.index, j.body_b.index, j.local_anchor_a.x(),
                           j.local_anchor_a.y(), j.local_anchor_a.z(), j.local_anchor_b.x(),
                           j.local_anchor_b.y(), j.local_anchor_b.z(), j.spring.hertz,
                           j.spring.damping_ratio);
            }
          } else {
            softstep::DistanceJointDef j;
            j.body_a = pick(in, bodies);
            j.body_b = pick(in, bodies);
            j.local_anchor_a = in.ConsumeBool() ? Eigen::Vector3d::Zero() : vec(in);
            j.local_anchor_b = in.ConsumeBool() ? Eigen::Vector3d::Zero() : vec(in);
            j.rest_length = value(in);
            j.min_length = in.ConsumeBool() ? 0.0 : value(in);
            j.max_length = in.ConsumeBool() ? INFINITY : value(in);
            j.spring = spring(in);
            joints.push_back(world.create_distance_joint(j));
            if (verbose()) {
              std::fprintf(stderr,
                           "distance %u-%u ra (%g %g %g) rb (%g %g %g) rest %g min %g max %g "
                           "hertz %g zeta %g\n",
                           j.body_a.index, j.body_b.index, j.local_anchor_a.x(),
                           j.local_anchor_a.y(), j.local_anchor_a.z(), j.local_anchor_b.x(),
                           j.local_anchor_b.y(), j.local_anchor_b.z(), j.rest_length, j.min_length,
                           j.max_length, j.spring.hertz, j.spring.damping_ratio);
            }
          }
          break;
        }
        case 5:
          world.destroy_joint(pick(in, joints));
          break;
        case 6: {
          const BodyId b = pick(in, bodies);
          const int change = in.ConsumeIntegralInRange<int>(0, 5);
          switch (change) {
            case 0:
              world.set_position(b, vec(in));
              break;
            case 1:
              world.set_orientation(
                  b, softstep::Quaternion(value(in), value(in), value(in), value(in)));
              break;
            case 2:
              world.set_linear_velocity(b, vec(in));
              break;
            case 3:
              world.set_angular_velocity(b, vec(in));
              break;
            case 4:
              world.apply_impulse(b, vec(in), vec(in));
              break;
            default:
              world.set_mass_properties(b, value(in),
                                        softstep::solid_sphere_inertia(1.0, value(in)));
              break;
          }
          if (verbose()) {
            static constexpr const char* kChanges[] = {"set_position", "set_orientation",
                                                       "set_linear_velocity", "set_angular_velocity",
                                                       "apply_impulse", "set_mass_properties"};
            std::fprintf(stderr, "%s %u\n", kChanges[change], b.index);
          }
          break;
        }
        case 7: {
          softstep::WorldSettings s = world.settings();
          s.gravity = vec(in);
          s.substeps = in.ConsumeIntegralInRange<int>(-1, 6);
          s.relax_iterations = in.ConsumeIntegralInRange<int>(-1, 3);
          s.solve_iterations = in.ConsumeIntegralInRange<int>(0, 3);
          s.max_linear_speed = value(in);
          s.warm_start = in.ConsumeBool();
          s.sleeping = in.ConsumeBool();
          s.specialize = in.ConsumeBool();
          s.time_to_sleep = value(in);
          s.rigid_hertz = value(in);
          s.simd = static_cast<softstep::SimdWidth>(in.ConsumeIntegralInRange<int>(0, 3));
          s.solver = static_cast<softstep::SolverMode>(in.ConsumeIntegralInRange<int>(0, 2));
          s.geometric_stiffness = in.ConsumeBool();
          if (in.ConsumeBool()) {
            s.contact.hertz = value(in);
            s.contact.damping_ratio = value(in);
            s.contact.max_push_out_speed = value(in);
            s.contact.restitution_threshold = value(in);
            s.contact.friction_while_solving = in.ConsumeBool();
          }
          world.set_settings(s);
          if (verbose()) {
            std::fprintf(stderr,
                         "settings gravity (%g %g %g) substeps %d solve %d relax %d warm %d "
                         "rigid_hertz %g max_speed %g solver %d geometric_stiffness %d contact "
                         "%g Hz zeta %g push-out %g restitution threshold %g friction while "
                         "solving %d\n",
                         s.gravity.x(), s.gravity.y(), s.gravity.z(), s.substeps,
                         s.solve_iterations, s.relax_iterations, int(s.warm_start), s.rigid_hertz,
                         s.max_linear_speed, static_cast<int>(s.solver), int(s.geometric_stiffness),
                         s.contact.hertz, s.contact.damping_ratio, s.contact.max_push_out_speed,
                         s.contact.restitution_threshold, int(s.contact.friction_while_solving));
          }
          break;
        }
        case 10: {  // a revolute, prismatic, weld, swing-twist, wheel or motor joint with random controls
          if (joints.size() >= 48) break;
          const BodyId a = pick(in, bodies);
          const BodyId b = pick(in, bodies);
          const int type = in.ConsumeIntegralInRange<int>(0, 5);
          if (type == 0) {
            softstep::RevoluteJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            j.limit = limit(in);
            j.motor = motor<softstep::AngularMotor>(in);
            j.spring = in.ConsumeBool() ? softstep::AxisSpring{} : axis_spring(in);
            print_axis_controls(j.limit, j.motor.enabled, j.motor.speed, j.motor.max_torque,
                                j.spring);
            joints.push_back(world.create_joint(j));
          } else if (type == 1) {
            softstep::PrismaticJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            j.limit = limit(in);
            j.motor = motor<softstep::LinearMotor>(in);
            j.spring = in.ConsumeBool() ? softstep::AxisSpring{} : axis_spring(in);
            print_axis_controls(j.limit, j.motor.enabled, j.motor.speed, j.motor.max_force,
                                j.spring);
            joints.push_back(world.create_joint(j));
          } else if (type == 5) {
            softstep::SwingTwistJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            swing_twist_parts(in, j);
            joints.push_back(world.create_joint(j));
          } else if (type == 2) {
            softstep::WeldJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            j.linear = spring(in);
            j.angular = spring(in);
            joints.push_back(world.create_joint(j));
          } else if (type == 3) {
            softstep::WheelJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            j.spring = in.ConsumeBool() ? softstep::AxisSpring{} : axis_spring(in);
            j.sprung_mass = value(in);
            j.limit = limit(in);
            j.motor = motor<softstep::AngularMotor>(in);
            j.steering = value(in);
            joints.push_back(world.create_joint(j));
          } else {
            softstep::MotorJointDef j;
            j.body_a = a;
            j.body_b = b;
            frames(in, world, a, b, j.frame_a, j.frame_b);
            j.max_force = value(in);
            j.max_torque = value(in);
            j.linear = spring(in);
            j.angular = spring(in);
            joints.push_back(world.create_joint(j));
          }
          if (verbose()) std::fprintf(stderr, "angular joint type %d %u-%u\n", type, a.index, b.index);
          break;
        }
        case 11: {  // set_joint on a joint of the new types: one part changed
          const JointId id = pick(in, joints);
          switch (world.joint_type(id)) {
            case softstep::JointType::Revolute: {
              auto d = world.joint_def<softstep::RevoluteJointDef>(id);
              mutate(in, d);
              world.set_joint(id, d);
              break;
            }
            case softstep::JointType::Prismatic: {
              auto d = world.joint_def<softstep::PrismaticJointDef>(id);
              mutate(in, d);
              world.set_joint(id, d);
              break;
            }
            case softstep::JointType::Weld: {
              auto d = world.joint_def<softstep::WeldJointDef>(id);
              mutate(in, d);
              world.set_joint(id, d);
              break;
            }
            case softstep::JointType::SwingTwist: {
              auto d = world.joint_def<softstep::SwingTwistJointDef>(id);
              if (in.ConsumeBool()) {
                d.frame_b = frame(in);
              } else {
                swing_twist_parts(in, d);
              }
              world.set_joint(id, d);
              break;
            }
            case softstep::JointType::Wheel: {
              auto d = world.joint_def<softstep::WheelJointDef>(id);
              mutate(in, d);
              world.set_joint(id, d);
              break;
            }
            case softstep::JointType::Motor: {
              auto d = world.joint_def<softstep::MotorJointDef>(id);
              mutate(in, d);
              world.set_joint(id, d);
              break;
            }
            default:
              break;
          }
          if (verbose()) std::fprintf(stderr, "set_joint %u\n", id.index);
          break;
        }
        default: {
          const double dt = in.ConsumeBool() ? 1.0 / 60.0 : value(in);
          if (in.ConsumeBool()) {
            world.step(dt);
          } else {
            world.step(dt, manifolds(in, bodies));
          }
          if (verbose()) {
            std::fprintf(stderr, "step %g (substeps %d, joints %zu)\n", dt,
                         world.settings().substeps, world.joint_count());
            dump(world, bodies);
          }
          check_finite(world, bodies);
          break;
        }
      }
    } catch (const softstep::InvalidArgument&) {
      if (world.state_hash() != before) fail("a rejected call changed the world");
    }
  }
  return 0;
}
