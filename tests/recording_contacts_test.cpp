// Recordings of steps with contacts (issue 16 with issue 13's contact input): the manifolds
// given to each step are in the file and replayed to the bit, the contacts' warm-start cache is
// in the initial state (so a recording may start mid-simulation), a changed contact byte fails
// replay at its step, a cut or corrupted contact record is an error, and the replay is the same
// at 1 and 2 threads.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "contacts/analytic_contacts.hpp"
#include "frame_constants.hpp"
#include "recording_files.hpp"
#include "softstep/recording.hpp"
#include "softstep/scene_file.hpp"

namespace softstep::test {
namespace {

// Three stacks of four boxes on the ground, a bouncing ball (restitution), a ball rolling on
// a conveyor (rolling resistance, tangent speed, a manifold key) and a fast-rolling wheel given
// as a round shape (its radius): every field a manifold has.
struct ContactScene {
  static constexpr int kStacks = 3, kBoxes = 4;
  World world;
  BodyId ground, ball, roller, wheel;
  std::vector<std::vector<BodyId>> stacks;

  explicit ContactScene(const WorldSettings& s = {}) : world(s) {
    ground = add_ground(world);
    for (int k = 0; k < kStacks; ++k) {
      stacks.emplace_back();
      for (int i = 0; i < kBoxes; ++i)
        stacks.back().push_back(
            add_box(world, {3.0 * k, 0.5 + i + 0.005 * i, 0.1 * k}, 5.0, kUnitCubeHalf));
    }
    BodyDef d;
    d.position = {-3.0, 1.5, 0.0};
    d.mass = 2.0;
    d.inertia = solid_sphere_inertia(2.0, 0.25);
    d.linear_velocity = {0.5, 0.0, 0.3};
    ball = world.create_body(d);
    d.position = {-6.0, 0.25, 0.0};
    d.angular_velocity = {0.0, 0.0, -4.0};
    roller = world.create_body(d);
    d.position = {-9.0, 0.25, 0.0};
    d.linear_velocity = {5.0, 0.0, 0.0};
    d.angular_velocity = {0.0, 0.0, -20.0};
    wheel = world.create_body(d);
  }

  // The manifolds for the poses the world has now, always in this order and of these sizes in
  // the file: 12 box manifolds of 4 points without optional fields (290 bytes each), the ball
  // (1 point, restitution: 118 bytes), the roller (1 point, rolling resistance, tangent speed
  // and key: 142 bytes), the wheel (1 point, radius: 126 bytes).
  std::vector<ContactManifold> contacts() const {
    std::vector<ContactManifold> m;
    for (const auto& stack : stacks) {
      m.push_back(box_on_ground(world, ground, stack[0], kUnitCubeHalf, 0.0, 0.5));
      for (std::size_t i = 1; i < stack.size(); ++i)
        m.push_back(box_on_box(world, stack[i - 1], stack[i], kUnitCubeHalf));
    }
    ContactManifold b = sphere_on_ground(world, ground, ball, 0.25);
    b.restitution = 0.7;
    b.friction = 0.4;
    m.push_back(b);
    ContactManifold r = sphere_on_ground(world, ground, roller, 0.25);
    r.friction = 0.9;
    r.rolling_resistance = 0.02;
    r.tangent_speed = {0.3, -0.1};
    r.key = 0x1234567890ull;
    m.push_back(r);
    ContactManifold w = round_sphere_on_ground(world, ground, wheel, 0.25);
    w.friction = 0.8;
    m.push_back(w);
    return m;
  }

  void step() { world.step(kDt, contacts()); }
};

constexpr std::size_t kBoxManifoldBytes = 50 + 4 * 60;
constexpr std::size_t kBoxManifolds = ContactScene::kStacks * ContactScene::kBoxes;
// tag, dt, count, the manifolds, the motion hash
constexpr std::size_t kContactStepBytes = 1 + 8 + 4 + kBoxManifolds * kBoxManifoldBytes +
                                          (50 + 8 + 60) + (50 + 8 + 16 + 8 + 60) + (50 + 16 + 60) + 8;

// Where the records start: after the signature, version, scene and initial hash.
std::size_t first_record(const std::string& bytes) {
  std::uint64_t scene_size;
  std::memcpy(&scene_size, &bytes[12], sizeof scene_size);
  return 20 + scene_size + 8;
}

// Records `steps` contact steps after `before` unrecorded ones; the state hash after each
// recorded step.
std::vector<std::uint64_t> record(const std::string& path, int before, int steps,
                                  const WorldSettings& s = {}) {
  ContactScene scene(s);
  for (int i = 0; i < before; ++i) scene.step();
  scene.world.start_recording(path);
  std::vector<std::uint64_t> hashes;
  for (int i = 0; i < steps; ++i) {
    scene.step();
    hashes.push_back(scene.world.state_hash());
  }
  scene.world.stop_recording();
  return hashes;
}

// Replays and checks the state hash (bodies, joints, the contact cache) after every step.
ReplayReport replay_checking(const std::string& path, const std::vector<std::uint64_t>& hashes,
                             const ReplayHooks& hooks = {}) {
  ReplayHooks h = hooks;
  h.after_step = [&](World& world, long step, double) {
    ASSERT_LE(step, static_cast<long>(hashes.size()));
    EXPECT_EQ(world.state_hash(), hashes[static_cast<std::size_t>(step - 1)]) << "step " << step;
  };
  return replay_recording(path, h);
}

TEST(RecordingContacts, AStackReplaysBitForBitEveryStep) {
  const std::string path = temp_path("contacts_stack");
  const std::vector<std::uint64_t> hashes = record(path, 0, 60);
  const ReplayReport report = replay_checking(path, hashes);
  EXPECT_EQ(report.steps, 60);
  EXPECT_EQ(report.contact_steps, 60);
  EXPECT_EQ(report.contact_manifolds, 60 * long(kBoxManifolds + 3));
  EXPECT_EQ(report.state_hash, hashes.back());
  // Every step's record has the size the layout says (the flags left out the zero fields).
  const std::string bytes = read_bytes(path);
  EXPECT_EQ(bytes.size(), first_record(bytes) + 60 * kContactStepBytes + 9);
  std::filesystem::remove(path);
}

// Started after 40 contact steps: the warm-start cache is in the initial state, so the replay
// starts from the same impulses. Without it the initial state hash (which covers the cache)
// would differ and the replay would refuse to start.
// destroy_body takes the body's contacts out of the warm-start cache at once, not at the next
// step: a world whose destroyed boxes touched (each other and the ground) hashes and saves
// like one where they never did. The kept box's contact stays in both.
TEST(RecordingContacts, DestroyingABodyDropsItsCacheEntriesAtOnce) {
  const auto after_destroying = [](bool touched) {
    World world;
    const BodyId ground = add_ground(world);
    const BodyId kept = add_box(world, {0.0, 0.5, 0.0}, 5.0, kUnitCubeHalf);
    const BodyId lower = add_box(world, {5.0, 0.5, 0.0}, 5.0, kUnitCubeHalf);
    const BodyId upper = add_box(world, {5.0, 1.5, 0.0}, 5.0, kUnitCubeHalf);
    std::vector<ContactManifold> contacts{
        box_on_ground(world, ground, kept, kUnitCubeHalf, 0.0, 0.5)};
    if (touched) {
      contacts.push_back(box_on_ground(world, ground, lower, kUnitCubeHalf, 0.0, 0.5));
      contacts.push_back(box_on_box(world, lower, upper, kUnitCubeHalf));
    }
    world.step(kDt, contacts);
    world.destroy_body(upper);
    world.destroy_body(lower);
    return world;
  };
  const World touched = after_destroying(true), untouched = after_destroying(false);
  EXPECT_EQ(touched.state_hash(), untouched.state_hash());
  const std::string saved = save_scene_text(touched);
  EXPECT_EQ(saved, save_scene_text(untouched));
  EXPECT_NE(saved.find("\"contact_cache\""), std::string::npos) << "the kept box's contact";
}

TEST(RecordingContacts, ARecordingStartedMidSimulationCarriesTheWarmStartCache) {
  const std::string path = temp_path("contacts_mid");
  const std::vector<std::uint64_t> hashes = record(path, 40, 30);
  const std::string bytes = read_bytes(path);
  const std::string scene = bytes.substr(20, first_record(bytes) - 28);
  EXPECT_NE(scene.find("\"contact_cache\""), std::string::npos);
  const ReplayReport report = replay_checking(path, hashes);
  EXPECT_EQ(report.steps, 30);
  EXPECT_EQ(report.state_hash, hashes.back());

  // The cache is part of the state: a world loaded without it is a different world.
  ContactScene a;
  for (int i = 0; i < 40; ++i) a.step();
  World reloaded = load_scene_text(save_scene_text(a.world), "saved");
  EXPECT_EQ(reloaded.state_hash(), a.world.state_hash());
  nlohmann::json without = nlohmann::json::parse(save_scene_text(a.world));
  ASSERT_EQ(without["solver_state"].erase("contact_cache"), 1u);
  EXPECT_NE(load_scene_text(without.dump(), "no cache").state_hash(), a.world.state_hash());
  std::filesystem::remove(path);
}

TEST(RecordingContacts, AChangedContactFailsReplayAtItsStep) {
  const std::string path = temp_path("contacts_changed");
  record(path, 10, 20);
  const std::string bytes = read_bytes(path);
  const auto record_at = [&](int step) {
    return first_record(bytes) + std::size_t(step - 1) * kContactStepBytes;
  };
  // Manifold 5, point 2: its separation and its feature id (the point then starts cold).
  const auto point_at = [&](int step) {
    return record_at(step) + 13 + 5 * kBoxManifoldBytes + 50 + 2 * 60;
  };
  for (int step : {1, 7, 20}) {
    ASSERT_EQ(bytes[record_at(step)], 16) << "not a contact step record";
    std::string separation = bytes;
    double d;
    std::memcpy(&d, &separation[point_at(step) + 48], sizeof d);
    d += 1e-3;
    std::memcpy(&separation[point_at(step) + 48], &d, sizeof d);
    std::string feature = bytes;
    feature[point_at(step) + 56] ^= 0x40;
    for (const std::string* changed : {&separation, &feature}) {
      try {
        replay_recording_bytes(*changed, "changed.rec");
        ADD_FAILURE() << "replayed";
      } catch (const RecordingError& e) {
        EXPECT_NE(std::string(e.what()).find("step " + std::to_string(step) + " diverged"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("contact manifolds"), std::string::npos) << e.what();
      }
    }
  }
  std::filesystem::remove(path);
}

// Corrupted contact records are refused by name: a point count or flags no writer makes, a
// body the world does not have, a normal that is not a unit vector or a negative radius (the
// step's own validation).
TEST(RecordingContacts, CorruptedContactRecordsSayWhatIsWrong) {
  const std::string path = temp_path("contacts_corrupt");
  record(path, 0, 3);
  const std::string bytes = read_bytes(path);
  const std::size_t step2 = first_record(bytes) + kContactStepBytes;
  const std::size_t manifold3 = step2 + 13 + 3 * kBoxManifoldBytes;
  // The wheel's radius_b: the last byte of the double after its radius_a (0.25 = 3fd0...).
  const std::size_t wheel_radius_b =
      step2 + 13 + kBoxManifolds * kBoxManifoldBytes + (50 + 8 + 60) + (50 + 8 + 16 + 8 + 60) + 50 +
      8 + 7;
  ASSERT_EQ(bytes[wheel_radius_b], char(0x3f));
  struct Case {
    const char* what;
    std::size_t at;
    char value;
    const char* message;
  };
  const Case cases[] = {
      {"point count", manifold3 + 40, 7, "step 2: contacts[3] has 7 points"},
      {"no points", manifold3 + 40, 0, "step 2: contacts[3] has 0 points"},
      {"flags", manifold3 + 41, char(0x80), "step 2: contacts[3] has unknown flags 128"},
      {"body", manifold3 + 8, 99, "contacts[3].body_b"},
      {"normal", manifold3 + 16 + 7, 0x7f, "contacts[3].normal"},
      {"radius", wheel_radius_b, char(0xbf), "contacts[14].radius_b = -0.25"},
      {"count", step2 + 9 + 3, 0x40, "truncated"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::string changed = bytes;
    changed[c.at] = c.value;
    expect_replay_error(changed, "bad.rec", c.message);
  }
  std::filesystem::remove(path);
}

// Cut at every byte of a contact step record (and of the next record's start): an error that
// says the file is truncated or ends early, never a crash or a replay.
TEST(RecordingContacts, TruncatedAtEveryByteOfAContactRecordIsRefused) {
  const std::string path = temp_path("contacts_truncated");
  record(path, 5, 2);
  const std::string bytes = read_bytes(path);
  const std::size_t begin = first_record(bytes);
  for (std::size_t size = begin; size <= begin + kContactStepBytes + 1; ++size)
    expect_cut_refused(bytes, size);
  std::filesystem::remove(path);
}

// A recording made on 1 thread replays at 2 and the other way round, every step's state hash
// equal: the contacts' colouring and solve give the same bits at any thread count.
TEST(RecordingContacts, ReplaysIdenticallyAtOneAndTwoThreads) {
  for (int recorded_at : {1, 2}) {
    SCOPED_TRACE(recorded_at);
    const std::string path = temp_path("contacts_threads");
    WorldSettings s;
    s.threads = recorded_at;
    s.fixed_threads = true;
    const std::vector<std::uint64_t> hashes = record(path, 20, 40, s);
    ReplayHooks hooks;
    hooks.on_start = [&](World& world) {
      WorldSettings replay = world.settings();
      replay.threads = 3 - recorded_at;
      replay.fixed_threads = true;
      world.set_settings(replay);
    };
    EXPECT_EQ(replay_checking(path, hashes, hooks).steps, 40);
    std::filesystem::remove(path);
  }
}

// The contact settings are in the initial scene: a world with its own contact spring replays.
TEST(RecordingContacts, ContactSettingsAreInTheInitialState) {
  const std::string path = temp_path("contacts_settings");
  WorldSettings s;
  s.contact.hertz = 45.0;
  s.contact.damping_ratio = 3.0;
  s.contact.max_push_out_speed = 1.5;
  s.contact.restitution_threshold = 0.25;
  s.contact.friction_while_solving = false;
  const std::vector<std::uint64_t> hashes = record(path, 0, 20, s);
  EXPECT_EQ(replay_checking(path, hashes).steps, 20);
  ContactScene scene(s);
  EXPECT_EQ(load_scene_text(save_scene_text(scene.world), "s").settings().contact, s.contact);
  std::filesystem::remove(path);
}

// A contact step in a file that says version 2 is refused by its version.
TEST(RecordingContacts, AContactStepInAVersion2FileIsRefused) {
  const std::string path = temp_path("contacts_v2");
  record(path, 0, 2);
  std::string bytes = read_bytes(path);
  bytes[8] = 2;
  expect_replay_error(bytes, "v2.rec",
                      "record tag 16 does not exist in a recording of version 2");
  std::filesystem::remove(path);
}

// A scene file's contact cache is checked like every other field.
TEST(RecordingContacts, BadContactCacheEntriesAreNamed) {
  ContactScene scene;
  for (int i = 0; i < 3; ++i) scene.step();
  const std::string text = save_scene_text(scene.world);
  // Bodies 1 and 5 (the bottom boxes of two stacks) have no entry yet.
  const std::string good = "{\"a\":1,\"b\":5,\"points\":[[0,1.5,0.0,0.0,0.0,1.5]]}";
  struct Case {
    const char* entry;
    const char* message;
  };
  const Case cases[] = {
      {"{\"a\":0,\"b\":0,\"points\":[[0,1,0,0,0,1]]}", "/contact_cache/0/b"},
      {"{\"a\":0,\"b\":1,\"points\":[]}", "expected 1 to 4 points"},
      {"{\"a\":0,\"b\":1,\"points\":[[0,1,0,0,0]]}", "/contact_cache/0/points/0"},
      {"{\"a\":0,\"b\":1,\"points\":[[-1,1,0,0,0,1]]}", "feature id"},
      {"{\"a\":0,\"b\":1,\"points\":[[0,1e39,0,0,0,1]]}", "within float's range"},
      {"{\"a\":0,\"b\":99,\"points\":[[0,1,0,0,0,1]]}", "no such body"},
      {"{\"a\":0,\"b\":1,\"key\":-3,\"points\":[[0,1,0,0,0,1]]}", "/contact_cache/0/key"},
      {"{\"a\":0,\"b\":1,\"pts\":[[0,1,0,0,0,1]]}", "points"},
  };
  const std::size_t at = text.find("\"contact_cache\":[");
  ASSERT_NE(at, std::string::npos);
  const std::size_t list = at + std::strlen("\"contact_cache\":[");
  // The good entry loads (into a world that differs by it), a second one for the same pair
  // is refused.
  std::string once = text;
  once.insert(list, good + ",");
  EXPECT_NE(load_scene_text(once, "once").state_hash(), scene.world.state_hash());
  EXPECT_EQ(load_scene_text(text, "same").state_hash(), scene.world.state_hash());
  std::string twice = text;
  twice.insert(list, good + "," + good + ",");
  try {
    load_scene_text(twice, "twice");
    ADD_FAILURE() << "loaded";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("a second entry"), std::string::npos) << e.what();
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.entry);
    std::string bad = text;
    bad.insert(list, std::string(c.entry) + ",");
    try {
      load_scene_text(bad, "bad.json");
      ADD_FAILURE() << "loaded";
    } catch (const SceneFileError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace softstep::test

namespace softstep::test {
namespace {

// The fuzzer's seeds (tests/fuzz/recording_corpus) are real files of every version, and each
// replays step for step (tests/recording_seeds_test.cpp writes the version 1 ones,
// seed_every_call and seed_v3_contacts again when results change).
TEST(RecordingContacts, SeedsOfEveryVersionAreRead) {
  const std::string corpus = std::string(SOFTSTEP_SOURCE_DIR) + "/tests/fuzz/recording_corpus/";
  struct Seed {
    const char* name;
    std::uint32_t version;
    long steps;
  };
  const Seed seeds[] = {{"seed_chain_steps", 3, 6},
                        {"seed_every_call", 3, 4},
                        {"seed_v1_every_call", 1, 4},
                        {"seed_v2_forces_set_joint", 2, 2},
                        {"seed_v3_contacts", 3, 3}};
  for (const Seed& seed : seeds) {
    SCOPED_TRACE(seed.name);
    const std::string bytes = read_bytes(corpus + seed.name);
    ASSERT_GT(bytes.size(), 12u);
    std::uint32_t version;
    std::memcpy(&version, &bytes[8], sizeof version);
    EXPECT_EQ(version, seed.version);
#if SOFTSTEP_USE_FMA
    EXPECT_EQ(replay_recording(corpus + seed.name).steps, seed.steps);
#else
    // The seeds were written by an FMA build (the release preset). A build that does not fuse
    // multiply-adds rounds differently, so its replay reads them whole and then diverges at the
    // first step, and says so (README, "Recordings": bit for bit within one arithmetic).
    try {
      replay_recording(corpus + seed.name);
      ADD_FAILURE() << "replayed bit for bit without FMA";
    } catch (const RecordingError& e) {
      EXPECT_NE(std::string(e.what()).find("step 1 diverged"), std::string::npos) << e.what();
    }
#endif
  }
#if SOFTSTEP_USE_FMA
  EXPECT_EQ(replay_recording(corpus + "seed_v3_contacts").contact_manifolds, 15);
#endif
}

}  // namespace
}  // namespace softstep::test
