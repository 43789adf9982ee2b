// Contacts against closed forms: a box resting on the ground (penetration of the contact
// spring), a box on a slope (static friction and sliding), a bouncing ball (restitution),
// stacks (warm starting, the load carried through every layer).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contacts/analytic_contacts.hpp"
#include "frame_constants.hpp"

namespace softstep::test {
namespace {

// At rest every normal row of the box has v = 0 and a constant impulse P, so its soft update
//   dP = -mass_scale m_eff (bias_rate s) - impulse_scale P = 0
// gives P = a bias_rate m_eff |s| = h omega^2 m_eff |s| (a = h omega (2 zeta + h omega)), and
// the four rows together carry gravity's impulse per sub-step, m g h. For a cube on its four
// bottom corners m_eff = m/4 per row (1/m plus (r x n) I^-1 (r x n) = 3/m), so
//   |s| = g / omega^2,   omega = 2 pi contact hertz:
// 0.276 mm at 30 Hz, whatever the mass.
TEST(ContactPhysics, BoxRestsAtThePenetrationOfTheContactSpringAndDoesNotDrift) {
  World world(settings_without_sleep());
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.3, 0.5, -0.2}, 100.0, kUnitCubeHalf);
  const double omega = 2.0 * std::numbers::pi * world.settings().contact.hertz;
  const double expected = 9.81 / (omega * omega);
  const auto step = [&] {
    const ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf);
    world.step(kDt, {&m, 1});
  };
  for (int i = 0; i < 120; ++i) step();  // 2 s to settle
  const Eigen::Vector3d settled = world.body(box).position;
  EXPECT_NEAR(0.5 - settled.y(), expected, 0.02 * expected);
  for (int i = 0; i < 10000; ++i) step();
  const BodyState end = world.body(box);
  // No drift once settled: the float solver's rounding on a 0.5 m coordinate is ~3e-8 m a
  // step, so 10,000 steps of a systematic creep would show as ~1e-4 m.
  EXPECT_NEAR(end.position.x(), settled.x(), 1e-6);
  EXPECT_NEAR(end.position.z(), settled.z(), 1e-6);
  EXPECT_NEAR(end.position.y(), settled.y(), 1e-7);
  EXPECT_NEAR(0.5 - end.position.y(), expected, 0.02 * expected);
  EXPECT_LT(end.angular_velocity.norm(), 1e-5);
  // The readings carry the weight: four normal impulses summing to m g h.
  const ContactReading& r = world.contact_readings().at(0);
  double total = 0.0;
  for (int k = 0; k < 4; ++k) {
    total += r.points[static_cast<std::size_t>(k)].normal_impulse;
    EXPECT_FALSE(r.points[static_cast<std::size_t>(k)].is_new);
  }
  const double h = kDt / world.settings().substeps;
  EXPECT_NEAR(total, 100.0 * 9.81 * h, 1e-3 * 100.0 * 9.81 * h);
}

// A slope by turning gravity: the ground stays y = 0 and gravity leans by `angle` towards +x.
struct SlopeRun {
  double x_at_1s, x_at_2s, v_at_1s, v_at_2s;
};

SlopeRun slide(double angle, double friction, bool friction_while_solving = true) {
  WorldSettings s = settings_without_sleep();
  s.contact.friction_while_solving = friction_while_solving;
  s.gravity = 9.81 * Eigen::Vector3d(std::sin(angle), -std::cos(angle), 0.0);
  World world(s);
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 10.0, kUnitCubeHalf);
  SlopeRun run{};
  for (int i = 1; i <= 120; ++i) {
    const ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf, 0.0, friction);
    world.step(kDt, {&m, 1});
    if (i == 60) {
      run.x_at_1s = world.body(box).position.x();
      run.v_at_1s = world.body(box).linear_velocity.x();
    }
  }
  run.x_at_2s = world.body(box).position.x();
  run.v_at_2s = world.body(box).linear_velocity.x();
  return run;
}

TEST(ContactPhysics, BoxOnASlopeStaysWhenTheSlopeIsBelowTheFrictionAngle) {
  const double angle = 25.0 * std::numbers::pi / 180.0;  // tan = 0.466 < 0.6
  const SlopeRun run = slide(angle, 0.6);
  // Static friction holds: the box settles into its springs in the first steps (a fraction of
  // a millimetre), then does not creep.
  EXPECT_LT(std::abs(run.x_at_2s), 1e-3);
  EXPECT_LT(std::abs(run.x_at_2s - run.x_at_1s), 1e-6);
  EXPECT_LT(std::abs(run.v_at_2s), 1e-5);
}

TEST(ContactPhysics, BoxOnASlopeSlidesWithTheKineticAcceleration) {
  const double angle = 40.0 * std::numbers::pi / 180.0;  // tan = 0.84 > 0.3
  const double friction = 0.3;
  const SlopeRun run = slide(angle, friction);
  const double expected = 9.81 * (std::sin(angle) - friction * std::cos(angle));
  // Between 1 s and 2 s (start-up left out): v gains a t, x gains the mean speed times t.
  EXPECT_NEAR(run.v_at_2s - run.v_at_1s, expected, 0.02 * expected);
  EXPECT_NEAR(run.x_at_2s - run.x_at_1s, 1.5 * expected, 0.02 * 1.5 * expected);
}

// Friction in the relax passes only: the warm start brings the last relax pass's friction
// impulse into each sub-step, so static friction holds as tightly and kinetic friction slides
// at the same acceleration.
TEST(ContactPhysics, FrictionWhileRelaxingOnlyHoldsAndSlidesAsTheKineticLaw) {
  const SlopeRun stays = slide(25.0 * std::numbers::pi / 180.0, 0.6, false);
  EXPECT_LT(std::abs(stays.x_at_2s), 1e-3);
  EXPECT_LT(std::abs(stays.x_at_2s - stays.x_at_1s), 1e-6);
  EXPECT_LT(std::abs(stays.v_at_2s), 1e-5);
  const double angle = 40.0 * std::numbers::pi / 180.0;
  const SlopeRun slides = slide(angle, 0.3, false);
  const double expected = 9.81 * (std::sin(angle) - 0.3 * std::cos(angle));
  EXPECT_NEAR(slides.v_at_2s - slides.v_at_1s, expected, 0.02 * expected);
  EXPECT_NEAR(slides.x_at_2s - slides.x_at_1s, 1.5 * expected, 0.02 * 1.5 * expected);
  // And it is another solve: the trajectory differs from friction in both passes.
  EXPECT_NE(slides.x_at_2s, slide(angle, 0.3).x_at_2s);
}

TEST(ContactPhysics, FrictionlessBoxSlidesWithTheFullSlopeAcceleration) {
  const double angle = 20.0 * std::numbers::pi / 180.0;
  const SlopeRun run = slide(angle, 0.0);
  const double expected = 9.81 * std::sin(angle);
  EXPECT_NEAR(run.v_at_2s - run.v_at_1s, expected, 0.01 * expected);
}

// Dropped from a height H above the ground with restitution e, a ball leaves with e times its
// impact speed and rises to e^2 H. Short steps keep the impact's timing error (the bounce
// starts at a step's end) below a percent.
TEST(ContactPhysics, BallBouncesToRestitutionSquaredOfItsDropHeight) {
  WorldSettings s = settings_without_sleep();
  s.substeps = 2;
  World world(s);
  const double r = 0.25, drop = 1.0, e = 0.8, dt = 1.0 / 480.0;
  const BodyId ground = add_ground(world);
  BodyDef d;
  d.position = {0.0, r + drop, 0.0};
  d.mass = 2.0;
  d.inertia = solid_sphere_inertia(2.0, r);
  const BodyId ball = world.create_body(d);
  double peak = 0.0;
  bool bounced = false;
  for (int i = 0; i < 2 * 480; ++i) {
    ContactManifold m = sphere_on_ground(world, ground, ball, r);
    m.restitution = e;
    world.step(dt, {&m, 1});
    const BodyState b = world.body(ball);
    if (b.linear_velocity.y() > 0.0) bounced = true;
    if (bounced) peak = std::max(peak, b.position.y() - r);
    if (bounced && b.linear_velocity.y() < 0.0) break;
  }
  ASSERT_TRUE(bounced);
  EXPECT_NEAR(peak, e * e * drop, 0.03 * e * e * drop);
}

// The kernels solve in the manifold's frame and add back only each body's velocity change:
// a contact whose rows apply nothing (apart and not closing within the sub-step) leaves both
// bodies exactly as a step without it does, at a slanted normal and on turned, spinning boxes
// of unequal sides. (Velocities turned into the frame and back would round.)
TEST(ContactPhysics, AContactThatAppliesNothingLeavesTheBodiesBitForBit) {
  const auto run = [](bool with_contact) {
    WorldSettings s = settings_without_sleep();
    s.gravity = Eigen::Vector3d::Zero();
    World world(s);
    const Eigen::Vector3d half(0.5, 0.3, 0.2);
    BodyDef d;
    d.mass = 40.0;
    d.inertia = solid_box_inertia(d.mass, 2.0 * half);
    d.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    const BodyId a = world.create_body(d);
    d.position = {0.2, 3.0, -0.1};
    d.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(-1.1, Eigen::Vector3d(3, -1, 2).normalized()));
    const BodyId b = world.create_body(d);
    world.set_linear_velocity(a, {0.3, 0.2, -0.1});
    world.set_angular_velocity(a, {1.0, -0.5, 0.7});
    world.set_linear_velocity(b, {-0.1, -0.4, 0.2});
    world.set_angular_velocity(b, {-0.3, 0.9, 0.4});
    ContactManifold m;
    m.body_a = a;
    m.body_b = b;
    m.normal = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
    m.friction = 0.6;
    m.rolling_resistance = 0.1;
    m.point_count = 2;
    m.points[0] = {{0.5, 0.3, 0.2}, {-0.5, -0.3, 0.2}, 2.0, 7};
    m.points[1] = {{-0.5, 0.3, -0.2}, {0.5, -0.3, -0.2}, 2.1, 9};
    for (int i = 0; i < 3; ++i) {
      if (with_contact) {
        world.step(kDt, {&m, 1});
      } else {
        world.step(kDt);
      }
    }
    EXPECT_EQ(world.contact_readings().size(), with_contact ? 1u : 0u);
    return std::pair{world.body(a), world.body(b)};
  };
  const auto with = run(true);
  const auto without = run(false);
  for (const auto& [x, y] :
       {std::pair{with.first, without.first}, std::pair{with.second, without.second}}) {
    EXPECT_EQ(x.position, y.position);
    EXPECT_EQ(x.orientation.coeffs(), y.orientation.coeffs());
    EXPECT_EQ(x.linear_velocity, y.linear_velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
  }
}

// A normal within the unit tolerance (1e-4) is taken as its direction: the kernels' frame must
// be a rotation. Along y the normalized normal is exactly the unit one, so the runs agree bit
// for bit; a normal used as given would push 1.00005 times as hard per unit of impulse.
TEST(ContactPhysics, ANearlyUnitNormalActsAsItsDirection) {
  const auto run = [](double length) {
    World world(settings_without_sleep());
    const BodyId ground = add_ground(world);
    const BodyId box = add_box(world, {0.3, 0.45, -0.2}, 100.0, kUnitCubeHalf);
    world.set_angular_velocity(box, {0.2, 0.1, -0.3});
    for (int i = 0; i < 30; ++i) {
      ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf);
      m.normal *= length;
      world.step(kDt, {&m, 1});
    }
    return world.body(box);
  };
  const BodyState unit = run(1.0);
  const BodyState nearly = run(1.0 + 5e-5);
  EXPECT_EQ(unit.position, nearly.position);
  EXPECT_EQ(unit.linear_velocity, nearly.linear_velocity);
  EXPECT_EQ(unit.angular_velocity, nearly.angular_velocity);
}

TEST(ContactPhysics, NoRestitutionPassWithoutRestitution) {
  WorldSettings s = settings_without_sleep();
  World world(s);
  world.set_profiling(true);
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  const ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf);
  world.step(kDt, {&m, 1});
  for (const StageEvent& ev : world.last_step_profile().thread_events.at(0)) {
    EXPECT_NE(ev.stage, Stage::Restitution);
  }
}

// A conveyor belt: the ground's surface moves at tangent_speed under the box, and friction
// brings the box to that speed (B's surface relative to A's, along tangent_directions).
TEST(ContactPhysics, TangentSpeedCarriesTheBoxAtTheBeltSpeed) {
  World world(settings_without_sleep());
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 5.0, kUnitCubeHalf);
  const Eigen::Vector2d belt(0.5, -1.25);
  for (int i = 0; i < 120; ++i) {
    ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf, 0.0, 0.8);
    m.tangent_speed = belt;
    world.step(kDt, {&m, 1});
  }
  const auto t = tangent_directions(Eigen::Vector3d::UnitY());
  const Eigen::Vector3d expected = belt.x() * t[0] + belt.y() * t[1];
  EXPECT_LT((world.body(box).linear_velocity - expected).norm(), 1e-3);
}

// Rolling resistance stops a rolling ball: without it a ball rolls on for ever (a point
// contact's friction does no work on a rolling ball); with it, the resisting torque
// c N decelerates the ball (m + I/r^2) v' = -c m g / r, i.e. v' = -(5/7) c g / r.
TEST(ContactPhysics, RollingResistanceDeceleratesARollingBall) {
  const double r = 0.5, c = 0.01, v0 = 2.0;
  const auto roll = [&](double resistance) {
    World world(settings_without_sleep());
    const BodyId ground = add_ground(world);
    BodyDef d;
    d.position = {0.0, r, 0.0};
    d.mass = 1.0;
    d.inertia = solid_sphere_inertia(1.0, r);
    d.linear_velocity = {v0, 0.0, 0.0};
    d.angular_velocity = {0.0, 0.0, -v0 / r};
    const BodyId ball = world.create_body(d);
    for (int i = 0; i < 60; ++i) {
      ContactManifold m = sphere_on_ground(world, ground, ball, r);
      m.friction = 0.5;
      m.rolling_resistance = resistance;
      world.step(kDt, {&m, 1});
    }
    return world.body(ball).linear_velocity.x();
  };
  EXPECT_NEAR(roll(0.0), v0, 1e-3);
  const double expected = v0 - 5.0 / 7.0 * c * 9.81 / r;
  EXPECT_NEAR(roll(c), expected, 0.05 * (v0 - expected));
}

// The plan shows the contact stages only while there are contacts, restitution only while
// some contact asks for it, and a step without contacts leaves no trace of them.
TEST(ContactPhysics, PlanShowsContactStagesOnlyWithContacts) {
  World world(settings_without_sleep());
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {0.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  const auto has = [&](PlanStage s) {
    const auto& st = world.step_plan().stages;
    return std::find(st.begin(), st.end(), s) != st.end();
  };
  world.step(kDt);
  EXPECT_FALSE(has(PlanStage::PrepareContacts));
  EXPECT_FALSE(has(PlanStage::Solve));  // no joints, no contacts: nothing to solve
  ContactManifold m = box_on_ground(world, ground, box, kUnitCubeHalf, 0.0, 0.0);
  world.step(kDt, {&m, 1});
  EXPECT_TRUE(has(PlanStage::PrepareContacts));
  EXPECT_TRUE(has(PlanStage::Solve));
  EXPECT_TRUE(has(PlanStage::Relax));
  EXPECT_FALSE(has(PlanStage::Restitution));
  EXPECT_FALSE(world.step_plan().contact_friction);
  EXPECT_EQ(world.step_plan().contact_manifolds, 1u);
  EXPECT_EQ(world.step_plan().contact_points, 4u);
  m = box_on_ground(world, ground, box, kUnitCubeHalf);
  m.restitution = 0.5;
  world.step(kDt, {&m, 1});
  EXPECT_TRUE(has(PlanStage::Restitution));
  EXPECT_TRUE(world.step_plan().contact_friction);
  world.step(kDt);
  EXPECT_FALSE(has(PlanStage::PrepareContacts));
  EXPECT_FALSE(has(PlanStage::Restitution));
  EXPECT_FALSE(has(PlanStage::Solve));
  EXPECT_EQ(world.step_plan().contact_manifolds, 0u);
}

// A step whose end puts a body to sleep rebuilds the plan (the awake bodies changed); the
// rebuilt plan still shows that step's contacts, as an unchanged plan does, until the next
// step hands its own. One box rests and falls asleep; the other slides without friction and
// stays awake.
TEST(ContactPhysics, PlanKeepsTheStepsContactsWhenTheStepPutsABodyToSleep) {
  WorldSettings s;
  s.time_to_sleep = 0.25;
  World world(s);
  const BodyId ground = add_ground(world);
  const BodyId resting = add_box(world, {0.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  const BodyId sliding = add_box(world, {3.0, 0.5, 0.0}, 1.0, kUnitCubeHalf);
  world.set_linear_velocity(sliding, {1.0, 0.0, 0.0});
  bool fell_asleep = false;
  for (int i = 0; i < 120 && !fell_asleep; ++i) {
    std::array<ContactManifold, 2> m{
        box_on_ground(world, ground, resting, kUnitCubeHalf),
        box_on_ground(world, ground, sliding, kUnitCubeHalf, 0.0, 0.0)};
    const std::uint64_t builds = world.step_plan().builds;
    world.step(kDt, m);
    fell_asleep = !world.is_awake(resting);
    if (!fell_asleep) continue;
    const StepPlan& plan = world.step_plan();
    ASSERT_GT(plan.builds, builds);  // the case of this test: the plan was rebuilt
    EXPECT_EQ(plan.contact_manifolds, 2u);
    EXPECT_EQ(plan.contact_points, 8u);
    EXPECT_TRUE(plan.runs(PlanStage::PrepareContacts));
  }
  EXPECT_TRUE(fell_asleep);
  EXPECT_TRUE(world.is_awake(sliding));
}

// A column of boxes on the ground, each step's manifolds made from the poses.
struct Stack {
  World world;
  BodyId ground;
  std::vector<BodyId> boxes;
  std::vector<ContactManifold> contacts() const {
    std::vector<ContactManifold> out;
    out.push_back(box_on_ground(world, ground, boxes[0], kUnitCubeHalf));
    for (std::size_t i = 1; i < boxes.size(); ++i) {
      out.push_back(box_on_box(world, boxes[i - 1], boxes[i], kUnitCubeHalf));
    }
    return out;
  }
  void step() {
    const auto c = contacts();
    world.step(kDt, c);
  }
};

Stack make_stack(int count, const WorldSettings& s) {
  Stack st{World(s), {}, {}};
  st.ground = add_ground(st.world);
  for (int i = 0; i < count; ++i) {
    st.boxes.push_back(add_box(st.world, {0.0, 0.5 + i, 0.0}, 10.0, kUnitCubeHalf));
  }
  return st;
}

// Ten boxes stand still, and the contacts carry what they must: the manifold under box i holds
// the (10 - i) boxes above it, (10 - i) m g h per sub-step. Warm starting is what lets one
// Gauss-Seidel pass per sub-step carry that: each step starts from the last one's impulses,
// which the readings show unchanged from step to step.
TEST(ContactPhysics, StackOfTenStandsStillWithWarmStartedImpulses) {
  Stack st = make_stack(10, settings_without_sleep());
  // The boxes start just touching and drop into their springs: Gauss-Seidel's point order
  // turns that drop into a sway of a few millimetres, which dies out.
  double early_sway = 0.0, late_sway = 0.0;
  for (int i = 0; i < 600; ++i) {
    st.step();
    const Eigen::Vector3d top = st.world.body(st.boxes.back()).position;
    double& sway = i < 120 ? early_sway : late_sway;
    if (i < 120 || i >= 540) sway = std::max(sway, std::hypot(top.x(), top.z()));
  }
  EXPECT_LT(late_sway, 1e-3);
  EXPECT_LT(late_sway, 0.25 * early_sway);
  const double h = kDt / st.world.settings().substeps;
  const std::vector<ContactReading> before = st.world.contact_readings();
  st.step();
  const std::vector<ContactReading>& after = st.world.contact_readings();
  for (std::size_t i = 0; i < after.size(); ++i) {
    double total = 0.0;
    for (int k = 0; k < 4; ++k) {
      const auto& p = after[i].points[static_cast<std::size_t>(k)];
      EXPECT_FALSE(p.is_new);
      total += p.normal_impulse;
      EXPECT_NEAR(p.normal_impulse, before[i].points[static_cast<std::size_t>(k)].normal_impulse,
                  1e-3 * p.normal_impulse);
    }
    const double carried = double(10 - i) * 10.0 * 9.81 * h;
    EXPECT_NEAR(total, carried, 0.01 * carried) << "manifold " << i;
  }
}

// Twenty boxes for 10 s. The tower's tilt is held by its contact springs: each interface is a
// rotational spring of stiffness sum(m_eff omega^2 d^2) over its corners (d = 0.5 m; m_eff = m/4
// on the ground, m/8 between two boxes), loaded by the weight above it. That linearized chain
// is stable only above 16 Hz for 10 boxes and 46 Hz for 20 (the positive-definiteness of
// stiffness minus the gravity term): at the default 30 Hz a 20-box tower buckles because its
// springs are too soft, not because of the solver. So this tower gets 60 Hz contacts.
// Each interface sinks by its load over its stiffness: k g/omega^2 for the ground under k
// boxes, 2 k g/omega^2 between boxes (half the effective mass), 400 g/omega^2 in all.
TEST(ContactPhysics, TowerOfTwentyStandsForTenSeconds) {
  WorldSettings s = settings_without_sleep();
  s.contact.hertz = 60.0;
  Stack st = make_stack(20, s);
  double sway = 0.0;
  for (int i = 0; i < 600; ++i) {
    st.step();
    const Eigen::Vector3d top = st.world.body(st.boxes.back()).position;
    sway = std::max(sway, std::hypot(top.x(), top.z()));
  }
  const double omega = 2.0 * std::numbers::pi * s.contact.hertz;
  const double sink = 400.0 * 9.81 / (omega * omega);
  EXPECT_LT(sway, 0.05);  // a few centimetres of sway at 19.5 m, never more
  EXPECT_NEAR(19.5 - st.world.body(st.boxes.back()).position.y(), sink, 0.05 * sink);
  for (std::size_t i = 1; i < st.boxes.size(); ++i) {
    EXPECT_GT(st.world.body(st.boxes[i]).position.y(),
              st.world.body(st.boxes[i - 1]).position.y() + 0.99);
  }
}

double top_sink(const Stack& st) {
  return double(st.boxes.size()) - 0.5 - st.world.body(st.boxes.back()).position.y();
}

// Without warm starting, the same stack cannot carry its load in one pass per sub-step: it
// sinks far more (the property the warm start buys, not an accident of the scene).
TEST(ContactPhysics, WarmStartingIsWhatHoldsTheStack) {
  WorldSettings cold = settings_without_sleep();
  cold.warm_start = false;
  Stack with = make_stack(10, settings_without_sleep());
  Stack without = make_stack(10, cold);
  for (int i = 0; i < 120; ++i) {
    with.step();
    without.step();
  }
  EXPECT_LT(top_sink(with), 0.5 * top_sink(without));
}

}  // namespace
}  // namespace softstep::test
