// Bad input to the revolute, prismatic, weld, swing-twist, wheel and motor joints (create_joint,
// set_joint, joint_def,
// frames_at) is rejected with an InvalidArgument naming the field and showing the value, and
// the world is left exactly as it was (state_hash): the house style of validation_test.cpp.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "joints/joint_test_support.hpp"
#include "rejection_check.hpp"

namespace softstep {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct JointFixture {
  World world;
  BodyId ground, a, b, gone;
  JointId revolute, prismatic, weld, swing_twist, wheel, motor;
};

// A world with one joint of each type, stepped so that impulses and poses are non-trivial.
JointFixture make_world() {
  JointFixture f{World(), {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  f.ground = test::static_body(f.world);
  f.a = test::dynamic_body(f.world, {1, 0, 0}, 1.0, Eigen::Matrix3d::Identity() * 0.01);
  f.b = test::dynamic_body(f.world, {2, 0, 0}, 1.0, Eigen::Matrix3d::Identity() * 0.01);
  f.gone = test::dynamic_body(f.world, {3, 0, 0}, 1.0, Eigen::Matrix3d::Identity() * 0.01);
  f.world.destroy_body(f.gone);
  const JointFrames fa = frames_at(f.world, f.ground, f.a, {0.5, 0, 0}, Eigen::Vector3d::UnitZ());
  RevoluteJointDef r;
  r.body_a = f.ground;
  r.body_b = f.a;
  r.frame_a = fa.a;
  r.frame_b = fa.b;
  r.limit = {true, -1.0, 1.0};
  r.motor = {true, 0.5, 1.0};
  f.revolute = f.world.create_joint(r);
  const JointFrames fb = frames_at(f.world, f.a, f.b, {1.5, 0, 0}, Eigen::Vector3d::UnitX());
  PrismaticJointDef p;
  p.body_a = f.a;
  p.body_b = f.b;
  p.frame_a = fb.a;
  p.frame_b = fb.b;
  p.spring = {Spring::soft(2.0, 0.5), 0.0};
  f.prismatic = f.world.create_joint(p);
  WeldJointDef w;
  w.body_a = f.ground;
  w.body_b = f.b;
  w.frame_a = fb.a;  // any frames: a weld holds whatever they say
  w.frame_b = fb.b;
  w.angular = Spring::soft(3.0, 0.1);
  f.weld = f.world.create_joint(w);
  SwingTwistJointDef st;
  st.body_a = f.a;
  st.body_b = f.b;
  st.frame_a = fb.a;
  st.frame_b = fb.b;
  st.cone = {true, 0.6, 0.4};
  st.twist = {true, -0.5, 0.5};
  st.spring.spring = Spring::soft(2.0, 0.3);
  st.motor = {true, 0.2};
  f.swing_twist = f.world.create_joint(st);
  const JointFrames fw =
      frames_at(f.world, f.a, f.b, {1.5, 0, 0}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
  WheelJointDef wheel;
  wheel.body_a = f.a;
  wheel.body_b = f.b;
  wheel.frame_a = fw.a;
  wheel.frame_b = fw.b;
  wheel.spring = {Spring::soft(2.0, 0.5), 0.0};
  wheel.sprung_mass = 1.0;
  wheel.motor = {true, 1.0, 2.0};
  wheel.steering = 0.2;
  f.wheel = f.world.create_joint(wheel);
  MotorJointDef m;
  m.body_a = f.ground;
  m.body_b = f.b;
  m.frame_a = fb.a;
  m.frame_b = fb.b;
  m.max_force = 10.0;
  m.max_torque = 1.0;
  m.linear = Spring::soft(2.0, 1.0);
  f.motor = f.world.create_joint(m);
  for (int i = 0; i < 3; ++i) f.world.step(1.0 / 60.0);
  return f;
}

void expect_rejected(const std::function<void(JointFixture&)>& call, const std::string& field,
                     const std::string& value) {
  test::expect_rejected_on<JointFixture>(make_world, call, field, value);
}

// Every check is made twice: on create_joint with a new joint between a and b, and on
// set_joint of the fixture's joint of that type. Both must reject with the same field.
template <class Def>
void expect_def_rejected(const std::function<void(JointFixture&, Def&)>& mutate,
                         JointId JointFixture::*existing, const std::string& field,
                         const std::string& value) {
  expect_rejected(
      [&](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        d.body_a = f.a;
        d.body_b = f.b;
        mutate(f, d);
        f.world.create_joint(d);
      },
      field, value);
  expect_rejected(
      [&](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        mutate(f, d);
        f.world.set_joint(f.*existing, d);
      },
      field, value);
}

// The checks every frame-based joint shares: bodies, anchors, axes, references.
template <class Def>
void expect_frame_rejections(const std::string& type, JointId JointFixture::*existing) {
  using Mutate = std::function<void(JointFixture&, Def&)>;
  const auto check = [&](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<Def>(m, existing, type + "." + field, value);
  };
  check([](JointFixture&, Def& d) { d.frame_a.local_axis.setZero(); }, "frame_a.local_axis", "0");
  check(
      [](JointFixture&, Def& d) {
        d.frame_b.local_axis = {0.0, kNan, 1.0};
      },
      "frame_b.local_axis", "nan");
  check(
      [](JointFixture&, Def& d) {
        d.frame_a.local_axis = {kInf, 0.0, 0.0};
      },
      "frame_a.local_axis", "inf");
  check([](JointFixture&, Def& d) { d.frame_b.local_reference = 2.0 * d.frame_b.local_axis; },
        "frame_b.local_reference", "parallel");
  check([](JointFixture&, Def& d) { d.frame_a.local_reference.setZero(); },
        "frame_a.local_reference", "0");
  // Creating: the same body twice, an unknown or destroyed body. set_joint: bodies changed.
  expect_rejected(
      [existing](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        d.body_a = f.b;
        d.body_b = f.b;
        f.world.create_joint(d);
      },
      type + ".body_b", "same body");
  expect_rejected(
      [existing](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        d.body_a = f.gone;
        f.world.create_joint(d);
      },
      type + ".body_a", "BodyId{3");
  expect_rejected(
      [existing](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        d.body_b = BodyId{99, 0};
        f.world.create_joint(d);
      },
      type + ".body_b", "BodyId{99");
}

// A frame's anchor is named as the caller spells it ("RevoluteJointDef.frame_a.local_anchor"),
// and set_joint with a body changed names that body and the value given.
template <class Def>
void expect_anchor_and_body_change_named(const std::string& type, JointId JointFixture::*existing) {
  using Mutate = std::function<void(JointFixture&, Def&)>;
  const auto check = [&](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<Def>(m, existing, type + "." + field, value);
  };
  check([](JointFixture&, Def& d) { d.frame_a.local_anchor.y() = kNan; }, "frame_a.local_anchor",
        "nan");
  check([](JointFixture&, Def& d) { d.frame_b.local_anchor.z() = 2e9; }, "frame_b.local_anchor",
        "2e+09");
  expect_rejected(
      [existing](JointFixture& f) {
        Def d = f.world.joint_def<Def>(f.*existing);
        d.body_b = d.body_b == f.a ? f.b : f.a;
        f.world.set_joint(f.*existing, d);
      },
      type + ".body_b", "BodyId{");
}

TEST(JointValidation, AnchorsAndChangedBodiesNamedAsTheCallerSpellsThem) {
  expect_anchor_and_body_change_named<RevoluteJointDef>("RevoluteJointDef",
                                                        &JointFixture::revolute);
  expect_anchor_and_body_change_named<PrismaticJointDef>("PrismaticJointDef",
                                                         &JointFixture::prismatic);
  expect_anchor_and_body_change_named<WeldJointDef>("WeldJointDef", &JointFixture::weld);
  expect_anchor_and_body_change_named<SwingTwistJointDef>("SwingTwistJointDef",
                                                          &JointFixture::swing_twist);
  expect_anchor_and_body_change_named<WheelJointDef>("WheelJointDef", &JointFixture::wheel);
  expect_anchor_and_body_change_named<MotorJointDef>("MotorJointDef", &JointFixture::motor);
}

TEST(JointValidation, RevoluteFrames) {
  expect_frame_rejections<RevoluteJointDef>("RevoluteJointDef", &JointFixture::revolute);
}
TEST(JointValidation, PrismaticFrames) {
  expect_frame_rejections<PrismaticJointDef>("PrismaticJointDef", &JointFixture::prismatic);
}
TEST(JointValidation, WeldFrames) {
  expect_frame_rejections<WeldJointDef>("WeldJointDef", &JointFixture::weld);
}
TEST(JointValidation, SwingTwistFrames) {
  expect_frame_rejections<SwingTwistJointDef>("SwingTwistJointDef", &JointFixture::swing_twist);
}
TEST(JointValidation, WheelFrames) {
  expect_frame_rejections<WheelJointDef>("WheelJointDef", &JointFixture::wheel);
}
TEST(JointValidation, MotorFrames) {
  expect_frame_rejections<MotorJointDef>("MotorJointDef", &JointFixture::motor);
}

// Limits, motors and springs along the free axis (revolute and prismatic alike).
template <class Def>
void expect_axis_rejections(const std::string& type, JointId JointFixture::*existing,
                            const std::string& max_field) {
  using Mutate = std::function<void(JointFixture&, Def&)>;
  const auto check = [&](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<Def>(m, existing, type + "." + field, value);
  };
  // Named like DistanceJointDef's min/max: the field checked against the other, showing both.
  check(
      [](JointFixture&, Def& d) {
        d.limit = {true, 0.5, -0.25};
      },
      "limit.lower", "upper (-0.25)");
  check([](JointFixture&, Def& d) { d.limit = {true, kNan, 1.0}; }, "limit.lower", "nan");
  check([](JointFixture&, Def& d) { d.limit = {true, -1.0, kInf}; }, "limit.upper", "inf");
  check([](JointFixture&, Def& d) { d.motor.speed = kNan; }, "motor.speed", "nan");
  check(
      [&](JointFixture&, Def& d) {
        if constexpr (requires { d.motor.max_torque; }) {
          d.motor.max_torque = -2.0;
        } else {
          d.motor.max_force = -2.0;
        }
      },
      "motor." + max_field, "-2");
  check(
      [&](JointFixture&, Def& d) {
        if constexpr (requires { d.motor.max_torque; }) {
          d.motor.max_torque = kNan;
        } else {
          d.motor.max_force = kNan;
        }
      },
      "motor." + max_field, "nan");
  check(
      [](JointFixture&, Def& d) {
        d.spring = {Spring::rigid(), 0.0};
      },
      "spring.spring.hertz", "inf");
  check(
      [](JointFixture&, Def& d) {
        d.spring = {Spring::soft(-1.0, 0.5), 0.0};
      },
      "spring.spring.hertz", "-1");
  check(
      [](JointFixture&, Def& d) {
        d.spring = {Spring::soft(2.0, kNan), 0.0};
      },
      "spring.spring.damping_ratio", "nan");
  check(
      [](JointFixture&, Def& d) {
        d.spring = {Spring::soft(2.0, 0.5), kNan};
      },
      "spring.target", "nan");
}

TEST(JointValidation, RevoluteAxisControls) {
  expect_axis_rejections<RevoluteJointDef>("RevoluteJointDef", &JointFixture::revolute,
                                           "max_torque");
}
TEST(JointValidation, PrismaticAxisControls) {
  expect_axis_rejections<PrismaticJointDef>("PrismaticJointDef", &JointFixture::prismatic,
                                            "max_force");
}

TEST(JointValidation, WheelAxisControls) {
  expect_axis_rejections<WheelJointDef>("WheelJointDef", &JointFixture::wheel, "max_torque");
}

// The sprung mass the spring's hertz refers to must be there when the spring is soft.
TEST(JointValidation, WheelSprungMassAndSteering) {
  using Mutate = std::function<void(JointFixture&, WheelJointDef&)>;
  const auto check = [](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<WheelJointDef>(m, &JointFixture::wheel, "WheelJointDef." + field, value);
  };
  check([](JointFixture&, WheelJointDef& d) { d.sprung_mass = 0.0; }, "sprung_mass", "0");
  check([](JointFixture&, WheelJointDef& d) { d.sprung_mass = -300.0; }, "sprung_mass", "-300");
  // Positive but below a body's smallest mass (1e-9 kg): its float spring overflowed to NaN.
  check([](JointFixture&, WheelJointDef& d) { d.sprung_mass = 1e-40; }, "sprung_mass", "1e-40");
  check([](JointFixture&, WheelJointDef& d) { d.sprung_mass = kNan; }, "sprung_mass", "nan");
  check([](JointFixture&, WheelJointDef& d) { d.sprung_mass = 2e9; }, "sprung_mass", "2e+09");
  check([](JointFixture&, WheelJointDef& d) { d.steering = kInf; }, "steering", "inf");
  // A free spring needs no sprung mass.
  JointFixture f = make_world();
  WheelJointDef d = f.world.joint_def<WheelJointDef>(f.wheel);
  d.spring.spring = Spring::free();
  d.sprung_mass = 0.0;
  EXPECT_NO_THROW(f.world.set_joint(f.wheel, d));
}

TEST(JointValidation, MotorCapsAndSprings) {
  using Mutate = std::function<void(JointFixture&, MotorJointDef&)>;
  const auto check = [](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<MotorJointDef>(m, &JointFixture::motor, "MotorJointDef." + field, value);
  };
  check([](JointFixture&, MotorJointDef& d) { d.max_force = -1.0; }, "max_force", "-1");
  check([](JointFixture&, MotorJointDef& d) { d.max_torque = kNan; }, "max_torque", "nan");
  check([](JointFixture&, MotorJointDef& d) { d.max_force = 2e9; }, "max_force", "2e+09");
  check([](JointFixture&, MotorJointDef& d) { d.linear = Spring::free(); }, "linear.hertz", "0");
  check([](JointFixture&, MotorJointDef& d) { d.angular = Spring::soft(-2.0, 1.0); },
        "angular.hertz", "-2");
}

TEST(JointValidation, WeldSprings) {
  using Mutate = std::function<void(JointFixture&, WeldJointDef&)>;
  const auto check = [](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<WeldJointDef>(m, &JointFixture::weld, "WeldJointDef." + field, value);
  };
  check([](JointFixture&, WeldJointDef& d) { d.linear = Spring::soft(-3.0, 0.1); }, "linear.hertz",
        "-3");
  check([](JointFixture&, WeldJointDef& d) { d.angular = Spring::soft(kNan, 0.1); },
        "angular.hertz", "nan");
  check([](JointFixture&, WeldJointDef& d) { d.angular = Spring::soft(2.0, -0.5); },
        "angular.damping_ratio", "-0.5");
}

// The cone's half-angles in (0, pi], the twist limit within [-pi, pi], the orientation spring
// soft or free towards a usable quaternion, the friction's torque >= 0.
TEST(JointValidation, SwingTwistLimitsSpringAndFriction) {
  using Mutate = std::function<void(JointFixture&, SwingTwistJointDef&)>;
  const auto check = [](Mutate m, const std::string& field, const std::string& value) {
    expect_def_rejected<SwingTwistJointDef>(m, &JointFixture::swing_twist,
                                            "SwingTwistJointDef." + field, value);
  };
  check([](JointFixture&, SwingTwistJointDef& d) { d.cone.half_angle_x = 0.0; },
        "cone.half_angle_x", "0");
  check([](JointFixture&, SwingTwistJointDef& d) { d.cone.half_angle_y = 3.5; },
        "cone.half_angle_y", "3.5");
  // Positive but below 1e-6 rad: the fuzzer's 1e-45 rad cone overflowed the float row.
  check([](JointFixture&, SwingTwistJointDef& d) { d.cone.half_angle_x = 1e-45; },
        "cone.half_angle_x", "1e-45");
  check([](JointFixture&, SwingTwistJointDef& d) { d.cone.half_angle_y = kNan; },
        "cone.half_angle_y", "nan");
  check(
      [](JointFixture&, SwingTwistJointDef& d) {
        d.cone = {false, kInf, 0.5};
      },
      "cone.half_angle_x", "inf");
  check(
      [](JointFixture&, SwingTwistJointDef& d) {
        d.twist = {true, 0.5, -0.25};
      },
      "twist.lower", "upper (-0.25)");
  check(
      [](JointFixture&, SwingTwistJointDef& d) {
        d.twist = {true, -4.0, 0.5};
      },
      "twist.lower", "-4");
  check(
      [](JointFixture&, SwingTwistJointDef& d) {
        d.twist = {true, -0.5, kNan};
      },
      "twist.upper", "nan");
  check([](JointFixture&, SwingTwistJointDef& d) { d.spring.spring = Spring::rigid(); },
        "spring.spring.hertz", "inf");
  check([](JointFixture&, SwingTwistJointDef& d) { d.spring.spring = Spring::soft(2.0, -1.0); },
        "spring.spring.damping_ratio", "-1");
  check([](JointFixture&,
           SwingTwistJointDef& d) { d.spring.target = Quaternion(0.0, 0.0, 0.0, 0.0); },
        "spring.target", "0");
  check([](JointFixture&,
           SwingTwistJointDef& d) { d.spring.target = Quaternion(1.0, kNan, 0.0, 0.0); },
        "spring.target", "nan");
  check([](JointFixture&, SwingTwistJointDef& d) { d.motor.max_torque = -1.0; }, "motor.max_torque",
        "-1");
}

// The typed accessors refuse a joint of another type; frames_at refuses what it cannot use.
TEST(JointValidation, WrongTypeAndFramesAt) {
  JointFixture f = make_world();
  const std::uint64_t before = f.world.state_hash();
  EXPECT_THROW(f.world.joint_def<WeldJointDef>(f.revolute), InvalidArgument);
  EXPECT_THROW(f.world.joint_def<RevoluteJointDef>(f.prismatic), InvalidArgument);
  EXPECT_THROW(f.world.joint_def<PrismaticJointDef>(JointId{77, 0}), InvalidArgument);
  EXPECT_THROW(f.world.joint_def<SwingTwistJointDef>(f.weld), InvalidArgument);
  EXPECT_THROW(f.world.set_joint(f.weld, f.world.joint_def<RevoluteJointDef>(f.revolute)),
               InvalidArgument);
  EXPECT_THROW(frames_at(f.world, f.a, f.b, {0, 0, 0}, Eigen::Vector3d::Zero()), InvalidArgument);
  EXPECT_THROW(frames_at(f.world, f.a, f.b, {kNan, 0, 0}, Eigen::Vector3d::UnitZ()),
               InvalidArgument);
  EXPECT_THROW(frames_at(f.world, f.a, f.gone, {0, 0, 0}, Eigen::Vector3d::UnitZ()),
               InvalidArgument);
  EXPECT_THROW(frames_at(f.world, f.a, f.b, {0, 0, 0}, Eigen::Vector3d::UnitZ(),
                         Eigen::Vector3d(0, 0, 2)),
               InvalidArgument);
  EXPECT_THROW(f.world.joint_def<WheelJointDef>(f.motor), InvalidArgument);
  EXPECT_THROW(f.world.set_joint(f.wheel, f.world.joint_def<MotorJointDef>(f.motor)),
               InvalidArgument);
  EXPECT_EQ(f.world.state_hash(), before);
}

}  // namespace
}  // namespace softstep
