// The recording fuzzer's seeds (tests/fuzz/recording_corpus/seed_chain_steps, seed_every_call,
// seed_v1_every_call, seed_v3_contacts) are written here, so that they can be written again when a
// change meant to change results (a new state hash, a re-frozen golden table) leaves the committed
// ones stopping at their first hash: the fuzzer must start from files that replay through, not from
// files its reader refuses at the start. To rewrite them (an FMA build, as the release and tests
// presets are):
//   SOFTSTEP_WRITE_SEEDS=tests/fuzz/recording_corpus
//     build/tests/tests/softstep_tests --gtest_filter=RecordingSeeds.*   (one command line)
// and commit only the seeds whose replay broke: the others were written by older versions of
// this library on purpose (their settings lack fields added since, which the reader must still
// accept), and a rewrite would replace them with today's format.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "contacts/analytic_contacts.hpp"
#include "frame_constants.hpp"
#include "recording_files.hpp"
#include "scenes/chain_scene.hpp"
#include "softstep/recording.hpp"
#include "softstep/softstep.hpp"

namespace softstep::test {
namespace {

// The recording of `calls` made on `world` (recording starts before them).
std::string recording_of(World& world, const std::function<void(World&)>& calls) {
  const std::string path = temp_path("seed");
  world.start_recording(path);
  calls(world);
  world.stop_recording();
  const std::string bytes = read_bytes(path);
  std::filesystem::remove(path);
  return bytes;
}

// A four-link chain stepped six times: steps only.
std::string chain_steps() {
  World world;
  scenes::ChainOptions chain;
  chain.links = 4;
  scenes::build_chain(world, chain);
  return recording_of(world, [](World& w) {
    for (int i = 0; i < 6; ++i) w.step(kDt);
  });
}

// Every record of version 1 (tags 1 to 12), on a pendulum and the bodies and joints created
// while recording.
std::string every_call() {
  World world;
  BodyDef ceiling;
  ceiling.type = BodyType::Static;
  const BodyId anchor = world.create_body(ceiling);
  BodyDef bob;
  bob.position = {1.0, 0.0, 0.0};
  bob.inertia = solid_sphere_inertia(1.0, 0.1);
  const BodyId first = world.create_body(bob);
  BallJointDef pin;
  pin.body_a = anchor;
  pin.body_b = first;
  pin.local_anchor_a = {0.0, 0.0, 0.0};
  pin.local_anchor_b = {-1.0, 0.0, 0.0};
  world.create_ball_joint(pin);
  return recording_of(world, [&](World& w) {
    w.step(kDt);
    BodyDef next = bob;
    next.position = {2.0, 0.0, 0.0};
    const BodyId second = w.create_body(next);
    DistanceJointDef rope;
    rope.body_a = first;
    rope.body_b = second;
    rope.rest_length = 1.0;
    rope.spring = Spring::soft(5.0, 0.3);
    const JointId link = w.create_distance_joint(rope);
    w.step(kDt);
    w.set_position(second, {2.0, -0.1, 0.0});
    w.set_orientation(second, Quaternion(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())));
    w.set_linear_velocity(second, {0.0, 0.5, 0.0});
    w.set_angular_velocity(second, {0.0, 0.0, 1.0});
    w.set_mass_properties(second, 2.0, solid_sphere_inertia(2.0, 0.1));
    w.apply_impulse(first, {0.0, 0.2, 0.0}, {1.0, 0.05, 0.0});
    w.step(kDt);
    w.destroy_joint(link);
    w.destroy_body(second);
    WorldSettings s = w.settings();
    s.substeps = 2;
    w.set_settings(s);
    w.step(kDt);
  });
}

// The same calls in a file that says version 1: they are all records version 1 had, so the
// reader's version 1 path replays it through.
std::string every_call_version_1() {
  std::string bytes = every_call();
  const std::uint32_t version = 1;
  std::memcpy(&bytes[8], &version, sizeof version);
  return bytes;
}

// Steps with contacts: a box on the ground, a box on it and a round ball rolling on the ground
// (a radius, restitution and friction), five manifolds a step for three steps.
std::string contact_steps() {
  World world;
  const BodyId ground = add_ground(world);
  const BodyId lower = add_box(world, {0.0, 0.5, 0.0}, 5.0, kUnitCubeHalf);
  const BodyId upper = add_box(world, {0.1, 1.505, 0.0}, 5.0, kUnitCubeHalf);
  const BodyId side = add_box(world, {2.0, 0.5, 0.0}, 5.0, kUnitCubeHalf);
  const BodyId top = add_box(world, {2.0, 1.5, 0.05}, 5.0, kUnitCubeHalf);
  BodyDef d;
  d.position = {-2.0, 0.25, 0.0};
  d.mass = 2.0;
  d.inertia = solid_sphere_inertia(2.0, 0.25);
  d.linear_velocity = {2.0, 0.0, 0.0};
  d.angular_velocity = {0.0, 0.0, -8.0};
  const BodyId ball = world.create_body(d);
  const auto contacts = [&](const World& w) {
    ContactManifold rolling = round_sphere_on_ground(w, ground, ball, 0.25);
    rolling.friction = 0.8;
    rolling.restitution = 0.5;
    return std::vector<ContactManifold>{box_on_ground(w, ground, lower, kUnitCubeHalf, 0.0, 0.5),
                                        box_on_box(w, lower, upper, kUnitCubeHalf),
                                        box_on_ground(w, ground, side, kUnitCubeHalf, 0.0, 0.5),
                                        box_on_box(w, side, top, kUnitCubeHalf), rolling};
  };
  return recording_of(world, [&](World& w) {
    for (int i = 0; i < 3; ++i) w.step(kDt, contacts(w));
  });
}

struct Seed {
  const char* name;
  std::string (*write)();
  long steps;
};

constexpr Seed kSeeds[] = {
    {"seed_chain_steps", chain_steps, 6},
    {"seed_every_call", every_call, 4},
    {"seed_v1_every_call", every_call_version_1, 4},
    {"seed_v3_contacts", contact_steps, 3},
};

// Each seed as written now replays through (every step and the end state matched), and with
// SOFTSTEP_WRITE_SEEDS set goes to that folder.
TEST(RecordingSeeds, TheFuzzerSeedsAreWrittenHereAndReplay) {
  const char* into = std::getenv("SOFTSTEP_WRITE_SEEDS");
  for (const Seed& seed : kSeeds) {
    SCOPED_TRACE(seed.name);
    const std::string bytes = seed.write();
    const ReplayReport report = replay_recording_bytes(bytes, seed.name);
    EXPECT_EQ(report.steps, seed.steps);
    if (into != nullptr) {
      std::ofstream out(std::filesystem::path(into) / seed.name, std::ios::binary);
      out << bytes;
      ASSERT_TRUE(out.good()) << "cannot write into " << into;
    }
  }
  std::uint32_t version = 0;
  const std::string v1 = every_call_version_1();
  std::memcpy(&version, &v1[8], sizeof version);
  EXPECT_EQ(version, 1u);
}

}  // namespace
}  // namespace softstep::test
