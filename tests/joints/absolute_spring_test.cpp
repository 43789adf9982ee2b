// Springs in absolute units (spring.hpp, Spring::absolute): a stiffness k and damping c that
// the solver converts with the row's effective mass in each sub-step. The motion is the
// mass-spring-damper's of that k, c on the body's own mass (so the same spring is slower on a
// heavier body, unlike a relative one), it matches the relative spring of the same k, c, and
// JointReading::effective_mass is the analytic m_eff. (The wheel's suspension in N/m:
// wheel_test.cpp's CarBounce.)
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <unistd.h>

#include "joints/joint_test_support.hpp"
#include "rejection_check.hpp"
#include "scenes/joint_at.hpp"
#include "scenes/vehicle_scene.hpp"
#include "softstep/recording.hpp"
#include "softstep/scene_file.hpp"

namespace softstep {
namespace {

using test::kDt;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Undamped frequency (Hz) and damping ratio of an oscillation.
struct Oscillator {
  double hertz;
  double damping_ratio;
};

// The closed form: omega = sqrt(k/m), zeta = c / (2 sqrt(k m)).
Oscillator continuous(double k, double c, double m) {
  return {std::sqrt(k / m) / kTwoPi, c / (2.0 * std::sqrt(k * m))};
}

// What the solver integrates: the soft row is implicit Euler per sub-step h (talk 2:3),
//   v1 = (m v0 - h k x0) / (m + h c + h^2 k),  x1 = x0 + h v1,
// a linear map whose complex eigenvalues r e^(+-i theta) give the discrete motion's decay
// sigma = -ln r / h and damped frequency omega_d = theta / h, so an undamped frequency
// sqrt(sigma^2 + omega_d^2) and ratio sigma / that. It differs from the closed form by the
// step's own damping (about h omega / 2 on the ratio) and an O((h omega)^2) frequency shift.
Oscillator implicit_euler(double k, double c, double m, double h) {
  const double d = m + h * c + h * h * k;
  const double a11 = 1.0 - h * h * k / d, a12 = h * m / d, a21 = -h * k / d, a22 = m / d;
  const double trace = a11 + a22, det = a11 * a22 - a12 * a21;
  const std::complex<double> lambda(trace / 2.0, std::sqrt(det - trace * trace / 4.0));
  const double sigma = -std::log(std::abs(lambda)) / h;
  const double omega_d = std::arg(lambda) / h;
  const double omega = std::hypot(sigma, omega_d);
  return {omega / kTwoPi, sigma / omega};
}

// No gravity, no sleeping: the springs alone move the bodies, for as long as a test watches.
WorldSettings floating() {
  WorldSettings settings;
  settings.gravity = Eigen::Vector3d::Zero();
  settings.sleeping = false;
  return settings;
}

struct SliderRun {
  scenes::Bounce bounce;
  double effective_mass;
  std::vector<double> travel;
};

// A box of mass m on a prismatic joint along x through its centre, from a static ground, no
// gravity, released 0.1 m from the spring's target: the row's m_eff is m exactly.
SliderRun run_slider(double m, const Spring& spring, int steps) {
  World world(floating());
  const BodyId ground = test::static_body(world);
  const BodyId box =
      test::dynamic_body(world, {0.0, 1.0, 0.0}, m, solid_box_inertia(m, {0.4, 0.2, 0.3}));
  auto def = scenes::joint_at<PrismaticJointDef>(world, ground, box, {0.0, 1.0, 0.0},
                                                 Eigen::Vector3d::UnitX());
  def.spring = {spring, -0.1};  // unloaded 0.1 m behind where the box starts
  const JointId joint = world.create_joint(def);
  SliderRun r{{}, world.joint_reading(joint).effective_mass, {}};
  r.travel.push_back(world.joint_reading(joint).position);
  for (int i = 0; i < steps; ++i) {
    world.step(kDt);
    r.travel.push_back(world.joint_reading(joint).position);
  }
  r.bounce = scenes::measure_bounce(r.travel, -0.1, kDt);
  return r;
}

double substep() {
  return kDt / WorldSettings{}.substeps;
}

// k = 100 N/m, c = 4 N s/m on 4 kg: omega 5 rad/s (0.80 Hz), zeta 0.1; on 16 kg: 0.40 Hz,
// zeta 0.05. Over five periods the measured frequency and ratio are within 2 % of the
// implicit-Euler prediction (the sampling at 60 Hz of a 240 Hz motion, and the log
// decrement from sampled peaks, are the error), and the frequency within 1 % of the closed
// form ((h omega)^2 / 12 = 4e-5 is the step's shift); the ratio within h omega / 2 + 3 %.
TEST(AbsoluteSpring, SliderOscillatesAtSqrtKOverMAndHalvesOnFourTimesTheMass) {
  const double k = 100.0, c = 4.0, h = substep();
  const Spring spring = Spring::absolute(k, c);
  double previous_hertz = 0.0;
  for (double m : {4.0, 16.0}) {
    const SliderRun run = run_slider(m, spring, static_cast<int>(5.0 * kTwoPi * std::sqrt(m / k) / kDt));
    const Oscillator exact = implicit_euler(k, c, m, h);
    const Oscillator closed = continuous(k, c, m);
    EXPECT_NEAR(run.bounce.hertz, exact.hertz, 0.02 * exact.hertz) << m << " kg";
    EXPECT_NEAR(run.bounce.damping_ratio, exact.damping_ratio, 0.02 * exact.damping_ratio)
        << m << " kg";
    EXPECT_NEAR(run.bounce.hertz, closed.hertz, 0.01 * closed.hertz) << m << " kg";
    const double step_damping = h * kTwoPi * closed.hertz / 2.0;
    EXPECT_NEAR(run.bounce.damping_ratio, closed.damping_ratio,
                step_damping + 0.03 * closed.damping_ratio)
        << m << " kg";
    EXPECT_DOUBLE_EQ(run.effective_mass, m);
    if (previous_hertz > 0.0) {
      EXPECT_NEAR(run.bounce.hertz, previous_hertz / 2.0, 0.01 * previous_hertz);
    }
    previous_hertz = run.bounce.hertz;
  }
}

// The point of absolute units: a relative spring oscillates at its hertz whatever the mass.
TEST(AbsoluteSpring, ARelativeSpringKeepsItsFrequencyOnFourTimesTheMass) {
  const SliderRun light = run_slider(4.0, Spring::soft(0.8, 0.1), 400);
  const SliderRun heavy = run_slider(16.0, Spring::soft(0.8, 0.1), 400);
  EXPECT_NEAR(light.bounce.hertz, 0.8, 0.02 * 0.8);
  EXPECT_NEAR(heavy.bounce.hertz, light.bounce.hertz, 1e-3 * light.bounce.hertz);
}

// Absolute k = m_eff omega^2, c = 2 m_eff zeta omega is the relative spring (hertz, zeta) on
// that m_eff: the same coefficients, computed in float by two formulas (spring.hpp), so the
// same motion up to rounding: 1e-5 m of a 0.1 m swing over 300 steps.
TEST(AbsoluteSpring, EqualsTheRelativeSpringOfTheSameStiffnessAndDamping) {
  const double m = 3.0, hertz = 1.5, zeta = 0.2, omega = kTwoPi * hertz;
  const SliderRun relative = run_slider(m, Spring::soft(hertz, zeta), 300);
  const SliderRun absolute =
      run_slider(m, Spring::absolute(m * omega * omega, 2.0 * m * zeta * omega), 300);
  ASSERT_EQ(relative.travel.size(), absolute.travel.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < relative.travel.size(); ++i)
    worst = std::max(worst, std::abs(relative.travel[i] - absolute.travel[i]));
  EXPECT_LT(worst, 1e-5);
  // And they do move: a spring that did nothing would also agree.
  EXPECT_NEAR(relative.bounce.hertz, hertz, 0.02 * hertz);
}

// k = 0, c > 0 is a pure damper: no pull towards the target, the speed decays as
// m v' = -c v, by 1 / (1 + h c / m) per sub-step (implicit Euler), so after n sub-steps
// v = v0 (1 + h c/m)^-n; the box never turns back.
TEST(AbsoluteSpring, ZeroStiffnessIsAPureDamper) {
  World world(floating());
  const BodyId ground = test::static_body(world);
  const double m = 2.0, c = 3.0;
  const BodyId box = test::dynamic_body(world, {0.0, 1.0, 0.0}, m, solid_box_inertia(m, {0.4, 0.2, 0.3}));
  auto def = scenes::joint_at<PrismaticJointDef>(world, ground, box, {0.0, 1.0, 0.0},
                                                 Eigen::Vector3d::UnitX());
  def.spring = {Spring::absolute(0.0, c), 5.0};  // a target the damper must ignore
  world.create_joint(def);
  world.set_linear_velocity(box, {1.0, 0.0, 0.0});
  const int steps = 60;
  for (int i = 0; i < steps; ++i) world.step(kDt);
  const double h = substep();
  const double expected = std::pow(1.0 + h * c / m, -steps * WorldSettings{}.substeps);
  EXPECT_NEAR(world.body(box).linear_velocity.x(), expected, 1e-4);
}

// The distance joint's spring in N/m: a 5 kg ball hung by no gravity from a static point on
// a 1 m spring (rest length 1 m), released 0.1 m stretched along the line: m_eff = 5 kg, and
// k = 125 N/m, c = 5 N s/m give omega 5 rad/s, zeta 0.1; on 20 kg half the frequency. Bounds
// as for the slider.
TEST(AbsoluteSpring, DistanceSpringOscillatesAtSqrtKOverMAndHalvesOnFourTimesTheMass) {
  const double k = 125.0, c = 5.0;
  double previous_hertz = 0.0;
  for (double m : {5.0, 20.0}) {
    World world(floating());
    const BodyId ground = test::static_body(world);
    const BodyId ball = test::dynamic_body(world, {1.1, 0.0, 0.0}, m, solid_sphere_inertia(m, 0.1));
    DistanceJointDef d;
    d.body_a = ground;
    d.body_b = ball;
    d.rest_length = 1.0;
    d.spring = Spring::absolute(k, c);
    const JointId joint = world.create_distance_joint(d);
    EXPECT_DOUBLE_EQ(world.joint_reading(joint).effective_mass, m);
    std::vector<double> lengths{world.joint_reading(joint).position};
    const int steps = static_cast<int>(5.0 * kTwoPi / std::sqrt(k / m) / kDt);
    for (int i = 0; i < steps; ++i) {
      world.step(kDt);
      lengths.push_back(world.joint_reading(joint).position);
    }
    const scenes::Bounce b = scenes::measure_bounce(lengths, 1.0, kDt);
    const Oscillator exact = implicit_euler(k, c, m, substep());
    const Oscillator closed = continuous(k, c, m);
    EXPECT_NEAR(b.hertz, exact.hertz, 0.02 * exact.hertz) << m << " kg";
    EXPECT_NEAR(b.damping_ratio, exact.damping_ratio, 0.02 * exact.damping_ratio) << m << " kg";
    EXPECT_NEAR(b.hertz, closed.hertz, 0.01 * closed.hertz) << m << " kg";
    if (previous_hertz > 0.0) {
      EXPECT_NEAR(b.hertz, previous_hertz / 2.0, 0.01 * previous_hertz);
    }
    previous_hertz = b.hertz;
  }
}

// A revolute spring in N m/rad about z through the centre of a body of inertia I_zz = 0.5
// kg m^2 (A static: m_eff = I_zz): k = 2 N m/rad, c = 0.2 N m s/rad, omega = 2 rad/s,
// zeta 0.1; bounds as for the slider.
TEST(AbsoluteSpring, RevoluteSpringInNewtonMetresPerRadianOscillatesAtSqrtKOverI) {
  World world(floating());
  const BodyId ground = test::static_body(world);
  const double k = 2.0, c = 0.2, inertia = 0.5;
  const BodyId body = test::dynamic_body(world, {0.0, 1.0, 0.0}, 3.0,
                                         Eigen::Vector3d(0.3, 0.4, inertia).asDiagonal());
  auto def = scenes::joint_at<RevoluteJointDef>(world, ground, body, {0.0, 1.0, 0.0},
                                                Eigen::Vector3d::UnitZ());
  def.spring = {Spring::absolute(k, c), 0.0};
  const JointId joint = world.create_joint(def);
  world.set_angular_velocity(body, {0.0, 0.0, 0.4});
  EXPECT_NEAR(world.joint_reading(joint).effective_mass, inertia, 1e-12);
  std::vector<double> angles{world.joint_reading(joint).position};
  for (int i = 0; i < 5 * 190; ++i) {  // five periods of 3.14 s
    world.step(kDt);
    angles.push_back(world.joint_reading(joint).position);
  }
  const scenes::Bounce b = scenes::measure_bounce(angles, 0.0, kDt);
  const Oscillator exact = implicit_euler(k, c, inertia, substep());
  const Oscillator closed = continuous(k, c, inertia);
  EXPECT_NEAR(b.hertz, exact.hertz, 0.02 * exact.hertz);
  EXPECT_NEAR(b.damping_ratio, exact.damping_ratio, 0.02 * exact.damping_ratio);
  EXPECT_NEAR(b.hertz, closed.hertz, 0.01 * closed.hertz);
}

// JointReading::effective_mass: a slider between two free bodies through their centres sees
// 1/(1/m_a + 1/m_b); off the centre the rotation terms add (arm x n).I^-1(arm x n); a hinge
// sees n.(I_a^-1 + I_b^-1) n inverted; a distance joint through the centres the slider's
// 1/(1/m_a + 1/m_b); a ball joint has no one row (NaN).
TEST(AbsoluteSpring, JointReadingGivesTheAnalyticEffectiveMass) {
  World world(floating());
  const double ma = 2.0, mb = 6.0;
  const BodyId a = test::dynamic_body(world, {0.0, 0.0, 0.0}, ma, Eigen::Matrix3d::Identity() * 0.2);
  const BodyId b = test::dynamic_body(world, {1.0, 0.0, 0.0}, mb,
                                      Eigen::Vector3d(0.5, 0.6, 0.7).asDiagonal());
  const auto slide =
      scenes::joint_at<PrismaticJointDef>(world, a, b, {1.0, 0.0, 0.0}, Eigen::Vector3d::UnitX());
  EXPECT_NEAR(world.joint_reading(world.create_joint(slide)).effective_mass,
              1.0 / (1.0 / ma + 1.0 / mb), 1e-12);
  // Along y through B's centre: A's arm is (1, 0, 0), arm x y = z, A's term z.I_a^-1 z = 5.
  const auto across =
      scenes::joint_at<PrismaticJointDef>(world, a, b, {1.0, 0.0, 0.0}, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(world.joint_reading(world.create_joint(across)).effective_mass,
              1.0 / (1.0 / ma + 1.0 / mb + 1.0 / 0.2), 1e-12);
  const auto hinge =
      scenes::joint_at<RevoluteJointDef>(world, a, b, {0.5, 0.0, 0.0}, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(world.joint_reading(world.create_joint(hinge)).effective_mass,
              1.0 / (1.0 / 0.2 + 1.0 / 0.7), 1e-12);
  // A distance joint through the centres: 1/(1/m_a + 1/m_b), as the slider along the line.
  DistanceJointDef rod;
  rod.body_a = a;
  rod.body_b = b;
  rod.rest_length = 1.0;
  EXPECT_NEAR(world.joint_reading(world.create_distance_joint(rod)).effective_mass,
              1.0 / (1.0 / ma + 1.0 / mb), 1e-12);
  BallJointDef ball;
  ball.body_a = a;
  ball.body_b = b;
  EXPECT_TRUE(std::isnan(world.joint_reading(world.create_ball_joint(ball)).effective_mass));
}

// Bad k, c are rejected naming the field and the value, and so are absolute units on the
// joints whose springs do not take them; the world is left as it was.
struct SpringFixture {
  World world;
  BodyId ground, box;
};
SpringFixture make_fixture() {
  SpringFixture f{World(), {}, {}};
  f.ground = test::static_body(f.world);
  f.box = test::dynamic_body(f.world, {0.0, 1.0, 0.0}, 1.0, Eigen::Matrix3d::Identity() * 0.1);
  f.world.step(kDt);
  return f;
}

TEST(AbsoluteSpring, BadValuesAndJointsThatTakeNoAbsoluteUnitsAreRejected) {
  const auto slider_with = [](Spring s) {
    return [s](SpringFixture& f) {
      auto d = scenes::joint_at<PrismaticJointDef>(f.world, f.ground, f.box, {0.0, 1.0, 0.0},
                                                   Eigen::Vector3d::UnitX());
      d.spring.spring = s;
      f.world.create_joint(d);
    };
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  test::expect_rejected_on<SpringFixture>(make_fixture, slider_with(Spring::absolute(-1.0, 0.0)),
                                          "PrismaticJointDef.spring.spring.absolute_stiffness",
                                          "-1");
  test::expect_rejected_on<SpringFixture>(make_fixture, slider_with(Spring::absolute(1.0, nan)),
                                          "PrismaticJointDef.spring.spring.absolute_damping",
                                          "nan");
  // Positive but below 1e-6: 1 / (h (c + h k)) overflowed float and the bodies turned NaN.
  test::expect_rejected_on<SpringFixture>(make_fixture, slider_with(Spring::absolute(1e-40, 0.0)),
                                          "PrismaticJointDef.spring.spring.absolute_stiffness",
                                          "1e-40");
  test::expect_rejected_on<SpringFixture>(make_fixture, slider_with(Spring::absolute(0.0, 1e-40)),
                                          "PrismaticJointDef.spring.spring.absolute_damping",
                                          "1e-40");
  Spring stray = Spring::soft(2.0, 0.1);
  stray.absolute_stiffness = 5.0;  // a relative spring with an absolute field set
  test::expect_rejected_on<SpringFixture>(
      make_fixture, slider_with(stray), "PrismaticJointDef.spring.spring.absolute_stiffness", "5");
  Spring mixed = Spring::absolute(5.0, 1.0);
  mixed.hertz = 2.0;
  test::expect_rejected_on<SpringFixture>(make_fixture, slider_with(mixed),
                                          "PrismaticJointDef.spring.spring.hertz", "2");
  test::expect_rejected_on<SpringFixture>(
      make_fixture,
      [](SpringFixture& f) {
        BallJointDef d;
        d.body_a = f.ground;
        d.body_b = f.box;
        d.spring = Spring::absolute(10.0, 1.0);
        f.world.create_ball_joint(d);
      },
      "BallJointDef.spring.units", "Absolute");
  test::expect_rejected_on<SpringFixture>(
      make_fixture,
      [](SpringFixture& f) {
        WeldJointDef d = scenes::joint_at<WeldJointDef>(f.world, f.ground, f.box, {0.0, 1.0, 0.0},
                                                        Eigen::Vector3d::UnitX());
        d.angular = Spring::absolute(10.0, 1.0);
        f.world.create_joint(d);
      },
      "WeldJointDef.angular.units", "Absolute");
}

// A world with absolute springs (a revolute, a prismatic, a wheel) and a relative one saves
// to a scene file and loads back to the same state, and a recording of it replays bit for
// bit. (Files without the absolute keys load as relative: scene_file_test.cpp's files.)
TEST(AbsoluteSpring, SceneFileAndRecordingRoundTrip) {
  World world;
  scenes::VehicleOptions o;
  o.cars = 2;
  o.absolute_every = 2;  // car 0 absolute, car 1 relative
  o.on_rails = true;     // stepped without contacts
  const scenes::VehicleScene scene = scenes::build_vehicle(world, o);
  const BodyId box = test::dynamic_body(world, {0.0, 3.0, 9.0}, 2.0, Eigen::Matrix3d::Identity() * 0.1);
  auto hinge = scenes::joint_at<RevoluteJointDef>(world, scene.ground, box, {0.0, 3.0, 8.5},
                                                  Eigen::Vector3d::UnitX());
  hinge.spring = {Spring::absolute(30.0, 0.5), 0.2};
  const JointId hinged = world.create_joint(hinge);
  const std::string text = save_scene_text(world);
  EXPECT_NE(text.find("\"absolute_stiffness\""), std::string::npos);
  const World loaded = load_scene_text(text, "absolute.json");
  EXPECT_EQ(loaded.state_hash(), world.state_hash());

  const std::string path = (std::filesystem::temp_directory_path() /
                            ("softstep_absolute_spring_" + std::to_string(::getpid())))
                               .string();
  world.start_recording(path);
  for (int i = 0; i < 10; ++i) world.step(kDt);
  hinge.spring = {Spring::absolute(60.0, 0.0), 0.0};
  world.set_joint(hinged, hinge);
  for (int i = 0; i < 10; ++i) world.step(kDt);
  world.stop_recording();
  const ReplayReport report = replay_recording(path);
  EXPECT_EQ(report.steps, 20);
  EXPECT_EQ(report.state_hash, world.state_hash());
  std::filesystem::remove(path);
}

// The README's suspension example ("Springs in absolute units", cut out by tests/CMakeLists.txt):
// a 300 kg chassis corner (its centre at the wheel's, so gravity turns nothing) above a
// static wheel comes to rest at the travel m g / k = 300 * 9.81 / 47,000 (ratio 0.3 at 2 Hz
// decays by e^-(0.3 * 4 pi * 5) in 5 s: nothing left of the 6 cm bounce).
TEST(AbsoluteSpring, ReadmeSuspensionExampleRestsAtMgOverK) {
  World world;
  const Eigen::Vector3d wheel_centre(1.3, 0.35, 0.8);
  const BodyId chassis =
      test::dynamic_body(world, wheel_centre, 300.0, solid_box_inertia(300.0, {1.0, 0.6, 1.0}));
  const BodyId wheel = test::static_body(world, wheel_centre);
  {
#include "readme_examples/suspension_example.inc"
    for (int i = 0; i < 300; ++i) world.step(kDt);
    EXPECT_NEAR(world.joint_reading(suspension).position, 300.0 * 9.81 / 47'000.0, 1e-4);
    EXPECT_NEAR(world.joint_reading(suspension).effective_mass, 300.0, 1e-9);
  }
}

}  // namespace
}  // namespace softstep
