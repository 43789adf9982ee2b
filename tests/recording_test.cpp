// Recordings: a world recorded through every kind of call replays bit for bit; a recording
// changed at one step fails replay at that step; truncated and corrupted files are refused
// with a RecordingError that says where, never a crash.
#include "softstep/recording.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "recording_files.hpp"
#include "scenes/chain_scene.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

using test::expect_cut_refused;
using test::expect_replay_error;
using test::read_bytes;
using test::temp_path;

scenes::ChainScene every_call_chain(World& world) {
  scenes::ChainOptions chain;
  chain.links = 12;
  return scenes::build_chain(world, chain);
}

// Every kind of call between steps on the chain of every_call_chain. `knobs` changes the
// settings it sets, as an unchecked replay's adjust_settings does.
void make_every_call(World& world, const scenes::ChainScene& built, int steps_after,
                     const std::function<void(WorldSettings&)>& knobs = {}) {
  for (int i = 0; i < 5; ++i) world.step(1.0 / 60.0);
  BodyDef box;
  box.position = {1.0, 2.0, 0.5};
  box.mass = 2.0;
  const BodyId extra = world.create_body(box);
  BallJointDef ball;
  ball.body_a = built.links[0].back();
  ball.body_b = extra;
  ball.spring = Spring::soft(4.0, 0.5);
  const JointId soft = world.create_ball_joint(ball);
  DistanceJointDef rope;
  rope.body_a = built.anchors[0];
  rope.body_b = extra;
  rope.rest_length = 2.0;
  rope.max_length = 2.5;
  rope.spring = Spring::free();
  world.create_distance_joint(rope);
  world.step(1.0 / 60.0);
  world.set_position(built.links[0][3], {0.8, 0.1, 0.0});
  world.set_orientation(built.links[0][4],
                        Quaternion(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX())));
  world.set_linear_velocity(built.links[0][5], {0.0, 1.0, 0.0});
  world.set_angular_velocity(built.links[0][6], {0.0, 0.0, 2.0});
  world.set_mass_properties(built.links[0][7], 3.0, solid_sphere_inertia(3.0, 0.1));
  world.apply_impulse(built.links[0][8], {0.5, 0.0, 0.0}, {2.0, 0.1, 0.0});
  world.step(1.0 / 30.0);
  world.destroy_joint(soft);
  world.destroy_body(built.links[0][10]);
  WorldSettings s = world.settings();
  s.substeps = 6;
  s.gravity = {0.0, -5.0, 0.0};
  if (knobs) knobs(s);
  world.set_settings(s);
  for (int i = 0; i < steps_after; ++i) world.step(1.0 / 60.0);
}

// Records a chain and then every kind of call between steps; returns the final state_hash.
std::uint64_t record_every_call(const std::string& path, int steps_after) {
  World world;
  const scenes::ChainScene built = every_call_chain(world);
  world.start_recording(path);
  make_every_call(world, built, steps_after);
  world.stop_recording();
  return world.state_hash();
}

TEST(Recording, EveryCallReplaysBitForBit) {
  const std::string path = temp_path("every_call");
  const std::uint64_t hash = record_every_call(path, 20);
  long seen = 0;
  const ReplayReport report =
      replay_recording(path, [&](World&, long step, double) { seen = step; });
  EXPECT_EQ(report.steps, 27);
  EXPECT_EQ(seen, 27);
  EXPECT_EQ(report.calls, 14);  // 12 calls, and the 2 joints destroyed with the body
  EXPECT_EQ(report.state_hash, hash);
  std::filesystem::remove(path);
}

// An unchecked replay (softstep sweep FILE.rec) runs the recorded calls at other settings,
// held through the recording's own set_settings: it ends where the same calls made at those
// settings end, bit for bit. The same hooks in a checked replay fail at the first step, and an
// unchecked replay still refuses a cut file.
TEST(Recording, AnUncheckedReplayRunsTheCallsAtOtherSettings) {
  const std::string path = temp_path("unchecked");
  const std::uint64_t recorded = record_every_call(path, 20);
  const auto knobs = [](WorldSettings& s) {
    s.substeps = 2;
    s.relax_iterations = 0;
    s.solve_iterations = 3;
  };
  WorldSettings start;
  knobs(start);
  World world(start);
  make_every_call(world, every_call_chain(world), 20, knobs);

  ReplayHooks hooks;
  hooks.check = false;
  hooks.adjust_settings = knobs;
  long before = 0, after = 0;
  hooks.before_step = [&](World& w, long step, double) {
    EXPECT_EQ(step, after + 1);
    EXPECT_EQ(w.settings().substeps, 2);
    before = step;
  };
  hooks.after_step = [&](World&, long step, double) {
    EXPECT_EQ(step, before);
    after = step;
  };
  const ReplayReport report = replay_recording(path, hooks);
  EXPECT_EQ(report.steps, 27);
  EXPECT_EQ(after, 27);
  EXPECT_EQ(report.calls, 14);
  EXPECT_EQ(report.state_hash, world.state_hash());
  EXPECT_NE(report.state_hash, recorded);

  hooks.check = true;
  after = 0;
  try {
    replay_recording(path, hooks);
    ADD_FAILURE() << "a checked replay at other settings passed";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("step 1 diverged"), std::string::npos) << e.what();
  }
  hooks.check = false;
  const std::string bytes = read_bytes(path);
  try {
    replay_recording_bytes(bytes.substr(0, bytes.size() - 30), "cut.rec", hooks);
    ADD_FAILURE() << "replayed a cut file";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// The angular joints created while recording (through the generic create_joint, so the
// recorder sees their finished ids), set_joint on them, applied forces and torques, replay bit
// for bit.
TEST(Recording, AngularJointsAndAppliedForcesReplayBitForBit) {
  const std::string path = temp_path("angular");
  World world;
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId g = world.create_body(ground);
  world.start_recording(path);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 3; ++i) {
    BodyDef box;
    box.position = {0.5 * (i + 1), 0.0, 0.0};
    boxes.push_back(world.create_body(box));
  }
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), x = Eigen::Vector3d::UnitX();
  RevoluteJointDef hinge;
  hinge.body_a = g;
  hinge.body_b = boxes[0];
  const JointFrames hf = frames_at(world, g, boxes[0], {0.25, 0.0, 0.0}, z);
  hinge.frame_a = hf.a;
  hinge.frame_b = hf.b;
  hinge.limit = {true, -0.5, 0.4};
  hinge.motor = {true, 1.5, 20.0};
  hinge.spring = {Spring::soft(2.0, 0.3), 0.1};
  const JointId hinged = world.create_joint(hinge);
  PrismaticJointDef slider;
  slider.body_a = boxes[0];
  slider.body_b = boxes[1];
  const JointFrames sf = frames_at(world, boxes[0], boxes[1], {0.75, 0.0, 0.0}, x);
  slider.frame_a = sf.a;
  slider.frame_b = sf.b;
  slider.limit = {true, -0.1, 0.2};
  slider.motor = {true, -0.3, 5.0};
  slider.spring = {Spring::soft(3.0, 0.7), 0.05};
  world.create_joint(slider);
  WeldJointDef weld;
  weld.body_a = boxes[1];
  weld.body_b = boxes[2];
  const JointFrames wf = frames_at(world, boxes[1], boxes[2], {1.25, 0.0, 0.0}, z);
  weld.frame_a = wf.a;
  weld.frame_b = wf.b;
  weld.angular = Spring::soft(6.0, 0.5);
  const JointId welded = world.create_joint(weld);
  SwingTwistJointDef shoulder;
  shoulder.body_a = g;
  shoulder.body_b = boxes[2];
  const JointFrames stf = frames_at(world, g, boxes[2], {1.5, 0.0, 0.0}, x);
  shoulder.frame_a = stf.a;
  shoulder.frame_b = stf.b;
  shoulder.cone = {true, 0.8, 0.5};
  shoulder.twist = {true, -0.4, 0.6};
  shoulder.spring = {Spring::soft(1.5, 0.2), Quaternion(Eigen::AngleAxisd(0.2, z))};
  shoulder.motor = {true, 0.3};
  const JointId shouldered = world.create_joint(shoulder);
  for (int i = 0; i < 10; ++i) {
    world.apply_force(boxes[2], {0.0, 3.0, 1.0}, {1.6, 0.0, 0.1});
    world.apply_torque(boxes[1], {0.0, 0.5, 0.0});
    world.step(1.0 / 60.0);
  }
  // set_joint is recorded as the joint after the change.
  weld.linear = Spring::soft(8.0, 0.2);
  world.set_joint(welded, weld);
  hinge.motor.speed = -2.0;
  world.set_joint(hinged, hinge);
  shoulder.cone.half_angle_y = 0.3;
  world.set_joint(shouldered, shoulder);
  world.step(1.0 / 60.0);
  world.stop_recording();
  const ReplayReport report = replay_recording(path, [](World&, long, double) {});
  EXPECT_EQ(report.steps, 11);
  EXPECT_EQ(report.calls, 3 + 4 + 20 + 3);
  EXPECT_EQ(report.state_hash, world.state_hash());
  std::filesystem::remove(path);
}

// Wheel and motor joints created while recording, steered and re-targeted by set_joint.
TEST(Recording, WheelAndMotorJointsReplayBitForBit) {
  const std::string path = temp_path("wheel_motor");
  World world;
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId g = world.create_body(ground);
  world.start_recording(path);
  BodyDef box;
  box.position = {0.0, 1.0, 0.0};
  const BodyId chassis = world.create_body(box);
  box.position = {0.5, 0.6, 0.4};
  const BodyId wheel = world.create_body(box);
  const JointFrames wf = frames_at(world, chassis, wheel, box.position, Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ());
  WheelJointDef w;
  w.body_a = chassis;
  w.body_b = wheel;
  w.frame_a = wf.a;
  w.frame_b = wf.b;
  w.spring = {Spring::soft(3.0, 0.4), 0.05};
  w.sprung_mass = 2.0;
  w.limit = {true, -0.2, 0.2};
  w.motor = {true, 4.0, 2.0};
  const JointId wheeled = world.create_joint(w);
  MotorJointDef m;
  m.body_a = g;
  m.body_b = chassis;
  m.frame_a.local_anchor = {0.0, 1.0, 0.0};
  m.max_force = 40.0;
  m.max_torque = 5.0;
  m.linear = Spring::soft(2.0, 1.0);
  const JointId driven = world.create_joint(m);
  for (int i = 0; i < 10; ++i) world.step(1.0 / 60.0);
  w.steering = 0.4;
  world.set_joint(wheeled, w);
  m.frame_a.local_anchor = {0.5, 1.2, 0.0};
  world.set_joint(driven, m);
  for (int i = 0; i < 10; ++i) world.step(1.0 / 60.0);
  world.stop_recording();
  const ReplayReport report = replay_recording(path, [](World&, long, double) {});
  EXPECT_EQ(report.steps, 20);
  EXPECT_EQ(report.state_hash, world.state_hash());
  std::filesystem::remove(path);
}

TEST(Recording, AChangedStepFailsReplayAtThatStep) {
  const std::string path = temp_path("changed");
  record_every_call(path, 20);
  const std::string bytes = read_bytes(path);
  // The last 20 steps are 17-byte records (tag, dt, hash) before the 9-byte end record.
  for (int step : {8, 15, 27}) {
    std::string changed = bytes;
    const std::size_t at = changed.size() - 9 - std::size_t(27 - step + 1) * 17;
    ASSERT_EQ(changed[at], 1) << "not a step record";
    double dt;
    std::memcpy(&dt, &changed[at + 1], sizeof dt);
    dt *= 1.001;
    std::memcpy(&changed[at + 1], &dt, sizeof dt);
    expect_replay_error(changed, "changed.rec", "step " + std::to_string(step) + " diverged");
  }
  std::filesystem::remove(path);
}

TEST(Recording, TruncatedFilesAreRefusedEverywhere) {
  const std::string path = temp_path("truncated");
  record_every_call(path, 3);
  const std::string bytes = read_bytes(path);
  for (std::size_t size = 0; size < bytes.size(); size += 1 + size / 64)
    expect_cut_refused(bytes, size);
  std::filesystem::remove(path);
}

TEST(Recording, CorruptedFilesSayWhatIsWrong) {
  const std::string path = temp_path("corrupt");
  record_every_call(path, 3);
  const std::string bytes = read_bytes(path);
  struct Case {
    const char* what;
    std::size_t at;
    char value;
    const char* message;
  };
  const std::uint64_t scene_size = [&] {
    std::uint64_t n;
    std::memcpy(&n, &bytes[12], sizeof n);
    return n;
  }();
  const std::size_t first_record = 20 + scene_size + 8;
  const Case cases[] = {
      {"signature", 0, 'X', "not a softstep recording"},
      {"version", 8, 4, "version 4"},
      {"version 0", 8, 0, "version 0"},
      {"scene", 20 + 2, '!', "initial scene"},
      {"unknown tag", first_record, 77, "unknown record tag 77"},
      {"initial hash", 20 + scene_size, 0x5a, "does not load into the world that was recorded"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::string changed = bytes;
    changed[c.at] = c.value;
    expect_replay_error(changed, "bad.rec", c.message);
  }
  std::string extra = bytes + "x";
  EXPECT_THROW(replay_recording_bytes(extra, "long.rec"), RecordingError);
  std::filesystem::remove(path);
}

// Forces applied before start_recording are in its initial scene (issue 16): the replay
// starts from the same state hash and every step matches.
TEST(Recording, ForcesAppliedBeforeRecordingAreInItsInitialState) {
  const std::string path = temp_path("pending_force");
  std::uint64_t recorded = 0;
  {
    World world;
    scenes::ChainOptions chain;
    chain.links = 5;
    const scenes::ChainScene built = scenes::build_chain(world, chain);
    world.apply_force(built.links[0][3], {0.0, 40.0, 0.0}, world.body(built.links[0][3]).position);
    world.apply_torque(built.links[0][1], {1.0, 0.0, 0.0});
    world.start_recording(path);
    for (int i = 0; i < 3; ++i) world.step(1.0 / 60.0);
    world.stop_recording();
    recorded = world.state_hash();
  }
  const ReplayReport report = replay_recording(path);
  EXPECT_EQ(report.steps, 3);
  EXPECT_EQ(report.state_hash, recorded);
  std::filesystem::remove(path);
}

// A recording started on a world with sleeping islands replays bit for bit: its initial scene
// holds them (and the island woken while recording wakes in the replay too).
TEST(Recording, AWorldWithSleepingIslandsReplays) {
  const std::string path = temp_path("sleeping");
  World world;
  scenes::ChainOptions hanging;
  hanging.links = 4;
  hanging.chains = 2;
  hanging.layout = scenes::ChainLayout::Hanging;
  const scenes::ChainScene rest = scenes::build_chain(world, hanging);
  scenes::ChainOptions sideways;
  sideways.links = 5;
  scenes::build_chain(world, sideways);
  for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
  ASSERT_FALSE(world.is_awake(rest.links[0].back()));
  world.start_recording(path);
  for (int i = 0; i < 20; ++i) world.step(1.0 / 60.0);
  world.set_angular_velocity(rest.links[0][1], {0.0, 0.0, 1.0});
  for (int i = 0; i < 20; ++i) world.step(1.0 / 60.0);
  world.stop_recording();
  const ReplayReport report = replay_recording(path);
  EXPECT_EQ(report.steps, 40);
  EXPECT_EQ(report.state_hash, world.state_hash());
  std::filesystem::remove(path);
}

// A world that stepped replays (its scene holds the warm-start impulses); one whose ids a
// scene cannot rebuild (a body destroyed before recording) is named as such at the start.
TEST(Recording, AWorldThatSteppedReplaysOneWithDestroyedIdsIsNamed) {
  const std::string stepped = temp_path("stepped_ok");
  {
    World world;
    scenes::ChainOptions chain;
    chain.links = 5;
    scenes::build_chain(world, chain);
    for (int i = 0; i < 10; ++i) world.step(1.0 / 60.0);
    world.start_recording(stepped);
    for (int i = 0; i < 5; ++i) world.step(1.0 / 60.0);
    world.stop_recording();
  }
  EXPECT_EQ(replay_recording(stepped).steps, 5);
  std::filesystem::remove(stepped);

  const std::string path = temp_path("stepped");
  {
    World world;
    scenes::ChainOptions chain;
    chain.links = 5;
    scenes::build_chain(world, chain);
    world.step(1.0 / 60.0);
    world.destroy_body(world.create_body(BodyDef{}));  // a generation a scene does not hold
    world.start_recording(path);
    world.step(1.0 / 60.0);
    world.stop_recording();
  }
  try {
    replay_recording(path);
    ADD_FAILURE() << "replayed";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("start recording before the first destroy_body"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace softstep
