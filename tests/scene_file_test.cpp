// Scene files: every built-in scene and every joint type saved and loaded is the same world
// (equal state_hash, before and after steps), and each kind of broken file is refused with an
// error naming the file, the JSON path of the field and its value.
#include "softstep/scene_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scenes/bridge_scene.hpp"
#include "scenes/chain_scene.hpp"
#include "scenes/grid_scene.hpp"
#include "scenes/joint_zoo.hpp"
#include "scenes/ragdoll_scene.hpp"
#include "scenes/suspension_bridge.hpp"
#include "scenes/vehicle_scene.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

// Every body type and joint type with every field away from its default.
void build_every_feature(World& world) {
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.position = {0.5, 2.0, -1.0};
  ground.orientation = Quaternion(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  const BodyId g = world.create_body(ground);
  BodyDef driver;
  driver.type = BodyType::Kinematic;
  driver.position = {3.0, 1.0, 0.0};
  driver.linear_velocity = {0.0, 0.0, 1.5};
  driver.angular_velocity = {0.0, 2.0, 0.0};
  const BodyId k = world.create_body(driver);
  BodyDef box;
  box.position = {1.0, 0.0, 0.25};
  box.orientation = Quaternion(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()));
  box.linear_velocity = {0.1, -0.2, 0.3};
  box.angular_velocity = {1.0, 0.5, -0.25};
  box.mass = 2.5;
  box.inertia << 0.3, 0.01, 0.0, 0.01, 0.2, 0.02, 0.0, 0.02, 0.25;
  box.gravity_scale = 0.5;
  box.linear_damping = 0.1;
  box.angular_damping = 0.2;
  box.never_sleep = true;
  const BodyId b = world.create_body(box);
  BodyDef ball;
  ball.position = {2.0, -0.5, 0.0};
  ball.mass = 0.7;
  ball.inertia = solid_sphere_inertia(0.7, 0.05);
  const BodyId c = world.create_body(ball);

  BallJointDef pin;
  pin.body_a = g;
  pin.body_b = b;
  pin.local_anchor_a = {0.1, -0.2, 0.0};
  pin.local_anchor_b = {-0.3, 0.1, 0.05};
  world.create_ball_joint(pin);
  BallJointDef soft_pin = pin;
  soft_pin.body_a = b;
  soft_pin.body_b = c;
  soft_pin.spring = Spring::soft(7.5, 0.3);
  world.create_ball_joint(soft_pin);
  DistanceJointDef rope;
  rope.body_a = k;
  rope.body_b = c;
  rope.local_anchor_a = {0.0, 0.1, 0.0};
  rope.rest_length = 1.5;
  rope.min_length = 0.5;
  rope.max_length = 2.0;
  rope.spring = Spring::free();
  world.create_distance_joint(rope);
  DistanceJointDef rod;
  rod.body_a = g;
  rod.body_b = c;
  rod.rest_length = 2.5;
  world.create_distance_joint(rod);
  DistanceJointDef spring = rod;
  spring.body_a = k;
  spring.body_b = b;
  spring.spring = Spring::soft(3.0, 1.2);
  spring.min_length = 1.0;
  world.create_distance_joint(spring);
}

WorldSettings unusual_settings() {
  WorldSettings s;
  s.gravity = {0.5, -3.0, 0.25};
  s.substeps = 3;
  s.solve_iterations = 2;
  s.relax_iterations = 2;
  s.threads = 1;
  s.warm_start = false;
  s.rigid_hertz = 45.0;
  s.rigid_damping_ratio = 1.5;
  s.max_correction_speed = 2.0;
  s.geometric_stiffness = false;
  s.max_linear_speed = 500.0;
  s.simd = SimdWidth::Scalar;
  s.sleeping = false;
  s.sleep_linear_speed = 0.01;
  s.sleep_angular_speed = 0.02;
  s.time_to_sleep = 1.5;
  s.specialize = false;
  s.fixed_threads = true;
  return s;
}

struct BuiltScene {
  const char* name;
  WorldSettings settings;
  std::function<void(World&)> build;
};

std::vector<BuiltScene> built_scenes() {
  scenes::ChainOptions chain;
  chain.links = 30;
  chain.chains = 3;
  scenes::ChainOptions soft_chain = chain;
  soft_chain.joint = scenes::ChainJoint::Distance;
  soft_chain.spring = Spring::soft(5.0, 0.7);
  soft_chain.layout = scenes::ChainLayout::Hanging;
  soft_chain.tilt = 0.2;
  soft_chain.inertia_scale = 3.0;
  scenes::ChainOptions rope = chain;
  rope.joint = scenes::ChainJoint::Distance;
  rope.spring = Spring::free();
  rope.max_length = rope.link_spacing;
  rope.link_masses = {1.0, 2.0, 3.0, 100.0};
  rope.joint_gaps = {0.01, 0.02, 0.03, 0.04};
  scenes::GridOptions grid;
  grid.size = 8;
  grid.spring = Spring::soft(10.0, 0.5);
  scenes::BridgeOptions bridge;
  bridge.span = 40;
  bridge.loads = 4;
  // Every revolute, prismatic and weld variant (plain, limit, motor, spring, all; rigid and
  // soft welds), a chain of each.
  scenes::JointZooOptions zoo;
  zoo.chains = scenes::kZooJointKinds;
  zoo.links = 3;
  scenes::RagdollOptions ragdolls;
  ragdolls.count = 2;
  // Cars on wheel joints (steered, motored, sprung, limited; a scene file holds no contacts,
  // so here they fall through their ground), a suspension bridge with its cart, and motor
  // joints, rigid and soft, dragging boxes.
  scenes::VehicleOptions cars;
  cars.cars = 2;
  cars.steering = 0.1;
  scenes::SuspensionBridgeOptions suspension;
  suspension.stations = 5;
  const auto dragged_boxes = [](World& w) {
    BodyDef ground;
    ground.type = BodyType::Static;
    const BodyId g = w.create_body(ground);
    for (int i = 0; i < 3; ++i) {
      BodyDef box;
      box.position = {double(i), 1.0, 0.0};
      const BodyId b = w.create_body(box);
      MotorJointDef m;
      m.body_a = g;
      m.body_b = b;
      m.frame_a.local_anchor = {double(i), 2.0, 0.5};
      m.frame_a.local_axis = {0.0, 1.0, 0.0};  // unit: normalizing again keeps it
      m.frame_b.local_anchor = {0.1, 0.0, 0.0};
      m.max_force = 50.0 * (i + 1);
      m.max_torque = 3.0;
      if (i > 0) m.linear = Spring::soft(2.0, 0.7);
      if (i > 1) m.angular = Spring::soft(1.0, 1.0);
      w.create_joint(m);
    }
  };
  return {
      {"vehicle", {}, [=](World& w) { scenes::build_vehicle(w, cars); }},
      {"suspension_bridge", {}, [=](World& w) { scenes::build_suspension_bridge(w, suspension); }},
      {"motor_joints", {}, dragged_boxes},
      {"chain", {}, [=](World& w) { scenes::build_chain(w, chain); }},
      {"soft_hanging_distance_chain", {}, [=](World& w) { scenes::build_chain(w, soft_chain); }},
      {"rope_with_end_mass", {}, [=](World& w) { scenes::build_chain(w, rope); }},
      {"grid", {}, [=](World& w) { scenes::build_grid(w, grid); }},
      {"bridge", {}, [=](World& w) { scenes::build_bridge(w, bridge); }},
      {"every_feature", unusual_settings(), build_every_feature},
      {"joint_zoo", {}, [=](World& w) { scenes::build_joint_zoo(w, zoo); }},
      // Swing-twist joints with elliptical cones, twist limits and friction; hinges; ropes.
      {"ragdolls", {}, [=](World& w) { scenes::build_ragdolls(w, ragdolls); }},
  };
}

TEST(SceneFile, EveryBuiltInSceneRoundTripsBitForBit) {
  for (const BuiltScene& s : built_scenes()) {
    SCOPED_TRACE(s.name);
    World original(s.settings);
    s.build(original);
    const std::string text = save_scene_text(original);
    World loaded = load_scene_text(text, s.name);
    EXPECT_EQ(loaded.body_count(), original.body_count());
    EXPECT_EQ(loaded.joint_count(), original.joint_count());
    EXPECT_EQ(loaded.state_hash(), original.state_hash());
    // The settings the hash leaves out travel too.
    EXPECT_EQ(loaded.settings().simd, original.settings().simd);
    EXPECT_EQ(loaded.settings().threads, original.settings().threads);
    EXPECT_EQ(loaded.settings().specialize, original.settings().specialize);
    EXPECT_EQ(loaded.settings().fixed_threads, original.settings().fixed_threads);
    // Written again, the loaded world gives the same file.
    EXPECT_EQ(save_scene_text(loaded), text);
    // And it moves the same: the file lost nothing the solver uses.
    for (int i = 0; i < 20; ++i) {
      original.step(1.0 / 60.0);
      loaded.step(1.0 / 60.0);
    }
    EXPECT_EQ(loaded.state_hash(), original.state_hash());
  }
}

TEST(SceneFile, SavedAfterStepsKeepsPosesAndVelocities) {
  World original;
  scenes::ChainOptions chain;
  chain.links = 10;
  scenes::build_chain(original, chain);
  for (int i = 0; i < 30; ++i) original.step(1.0 / 60.0);
  World loaded = load_scene_text(save_scene_text(original), "stepped");
  const std::vector<BodyId> a = original.body_ids(), b = loaded.body_ids();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(loaded.body(b[i]).position, original.body(a[i]).position);
    EXPECT_EQ(loaded.body(b[i]).linear_velocity, original.body(a[i]).linear_velocity);
  }
}

// Loads applied for the next step (apply_force, apply_torque) are part of the world: a scene
// saved before that step reloads with them, bit for bit (the state hash covers them), and the
// step after the load is the step the original would have taken.
TEST(SceneFile, PendingForcesAndTorquesRoundTrip) {
  World original;
  scenes::ChainOptions chain;
  chain.links = 6;
  const scenes::ChainScene built = scenes::build_chain(original, chain);
  const BodyId pushed = built.links[0][2];
  original.apply_force(pushed, {3.0, -1.5, 0.25},
                       original.body(pushed).position + Eigen::Vector3d(0.0, 0.1, 0.0));
  original.apply_torque(built.links[0][4], {0.0, 0.0, 2.0});
  const std::string text = save_scene_text(original);
  EXPECT_NE(text.find("\"force\""), std::string::npos);
  World loaded = load_scene_text(text, "pending loads");
  EXPECT_EQ(loaded.state_hash(), original.state_hash());
  original.step(1.0 / 60.0);
  loaded.step(1.0 / 60.0);
  EXPECT_EQ(loaded.state_hash(), original.state_hash());
  // A force on a static body is refused with the body's path, as the API refuses it.
  const std::string bad = std::string(R"({"softstep_scene": 1, "settings": {}, "bodies": [)") +
                          R"({"type": "static", "position": [0, 0, 0], "force": [1, 0, 0]}]})";
  try {
    load_scene_text(bad, "static_force.json");
    ADD_FAILURE() << "loaded";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/bodies/0"), std::string::npos) << e.what();
  }
}

// A world saved after stepping reloads into the same world (issue 16): warm-start impulses,
// unwrapped hinge angles and rest times are in the file, so the state hash is equal and the
// next steps are the steps the original takes, for every joint type.
TEST(SceneFile, SavedAfterStepsReloadsBitForBitWithItsWarmStart) {
  WorldSettings s;
  s.sleeping = true;
  World original(s);
  scenes::build_joint_zoo(original, {14, 3});
  scenes::ChainOptions chain;
  chain.links = 8;
  scenes::build_chain(original, chain);
  for (int i = 0; i < 40; ++i) original.step(1.0 / 60.0);
  const std::string text = save_scene_text(original);
  EXPECT_NE(text.find("\"impulse\""), std::string::npos);
  EXPECT_NE(text.find("\"unwrapped_angle\""), std::string::npos);
  World loaded = load_scene_text(text, "stepped");
  EXPECT_EQ(loaded.state_hash(), original.state_hash());
  for (int i = 0; i < 20; ++i) {
    original.step(1.0 / 60.0);
    loaded.step(1.0 / 60.0);
  }
  EXPECT_EQ(loaded.state_hash(), original.state_hash());
  // A bad impulse is named by its path and value.
  std::string bad = text;
  const std::size_t at = bad.find("\"impulse\":[") + 11;
  bad.insert(at, "1e300, ");
  try {
    load_scene_text(bad, "bad_impulse.json");
    ADD_FAILURE() << "loaded";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/impulse/0"), std::string::npos) << e.what();
  }
}

// Two short chains hanging at rest from the ceiling (each its own island: the ceiling is
// static) and one laid out sideways that swings: after 60 steps the hanging ones sleep.
struct SleepingWorld {
  World world;
  std::vector<BodyId> hanging_ends;
  BodyId swinging_end;
  SleepingWorld() {
    scenes::ChainOptions hanging;
    hanging.links = 4;
    hanging.chains = 2;
    hanging.layout = scenes::ChainLayout::Hanging;
    const scenes::ChainScene rest = scenes::build_chain(world, hanging);
    for (const auto& links : rest.links) hanging_ends.push_back(links.back());
    scenes::ChainOptions sideways;
    sideways.links = 5;
    swinging_end = scenes::build_chain(world, sideways).links[0].back();
    for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
  }
};

// Sleeping islands are in the file (solver_state "sleeping_islands"): a world with some
// reloads asleep where it slept, with the same state hash, the same next steps while they
// sleep, and the same steps after one is woken.
TEST(SceneFile, SleepingIslandsRoundTripBitForBit) {
  SleepingWorld original;
  for (BodyId end : original.hanging_ends) ASSERT_FALSE(original.world.is_awake(end));
  ASSERT_TRUE(original.world.is_awake(original.swinging_end));
  const std::string text = save_scene_text(original.world);
  EXPECT_NE(text.find("\"sleeping_islands\":[["), std::string::npos);
  World loaded = load_scene_text(text, "sleeping");
  EXPECT_EQ(loaded.state_hash(), original.world.state_hash());
  EXPECT_EQ(save_scene_text(loaded), text);
  const BodyId woken = original.hanging_ends[1];  // the same id in both: no body was destroyed
  for (int i = 0; i < 40; ++i) {
    SCOPED_TRACE(i);
    if (i == 20) {
      original.world.set_linear_velocity(woken, {0.5, 0.0, 0.0});
      loaded.set_linear_velocity(woken, {0.5, 0.0, 0.0});
    }
    original.world.step(1.0 / 60.0);
    loaded.step(1.0 / 60.0);
    ASSERT_EQ(loaded.state_hash(), original.world.state_hash());
  }
  EXPECT_TRUE(loaded.is_awake(woken));
  EXPECT_FALSE(loaded.is_awake(original.hanging_ends[0]));
}

// A sleeping island that is not one (a static body, a body twice, a joint to an awake body),
// or islands in a world with sleeping off, is refused with its path.
TEST(SceneFile, BadSleepingIslandsAreNamed) {
  SleepingWorld original;
  const std::string text = save_scene_text(original.world);
  const std::size_t at = text.find("\"sleeping_islands\":[");
  ASSERT_NE(at, std::string::npos);
  const std::size_t list = at + std::strlen("\"sleeping_islands\":[");
  struct Case {
    const char* island;
    const char* message;
  };
  // Body 0 is the first chain's ceiling anchor (static); bodies 1..4 its links; the swinging
  // chain's links are the last bodies.
  const Case cases[] = {
      {"[0]", "a static body does not sleep"},
      {"[]", "expected a non-empty array"},
      {"[1,1]", "a body in two sleeping islands"},
      {"[999]", "expected a body's index"},
      {"[\"x\"]", "expected a body's index"},
      {"[1]", "a body in two sleeping islands"},  // 1 sleeps in the file's own island too
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.island);
    std::string bad = text;
    bad.insert(list, std::string(c.island) + ",");
    try {
      load_scene_text(bad, "bad.json");
      ADD_FAILURE() << "loaded";
    } catch (const SceneFileError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("/solver_state/sleeping_islands"), std::string::npos)
          << e.what();
    }
  }
  // Half an island: the rest of its chain is awake and jointed to it.
  const nlohmann::json root = nlohmann::json::parse(text);
  const auto& islands = root["solver_state"]["sleeping_islands"];
  ASSERT_EQ(islands.size(), 2u);
  ASSERT_EQ(islands[0].size(), 4u);
  nlohmann::json half = root;
  half["solver_state"]["sleeping_islands"][0].erase(3);
  try {
    load_scene_text(half.dump(), "half.json");
    ADD_FAILURE() << "loaded";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("a joint links this island to a movable body outside"),
              std::string::npos)
        << e.what();
  }
  nlohmann::json off = root;
  off["settings"]["sleeping"] = false;
  try {
    load_scene_text(off.dump(), "off.json");
    ADD_FAILURE() << "loaded";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("sleeping off"), std::string::npos) << e.what();
  }
}

TEST(SceneFile, SaveAndLoadThroughAFile) {
  World original;
  build_every_feature(original);
  const std::string path =
      (std::filesystem::temp_directory_path() / "softstep_scene_file_test.json").string();
  save_scene(original, path);
  EXPECT_EQ(load_scene(path).state_hash(), original.state_hash());
  std::filesystem::remove(path);
}

// A broken file: a change to a valid scene, and what the error must say.
struct Broken {
  const char* what;
  std::function<void(nlohmann::json&)> edit;      // on the parsed scene, or
  std::pair<const char*, const char*> text_edit;  // replace this text with that
  const char* path;                               // field(): the JSON path
  const char* message;                            // a part of the message (the value, the rule)
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(SceneFile, BrokenFilesAreRefusedWithTheirPathAndValue) {
  World world;
  build_every_feature(world);
  const std::string valid = save_scene_text(world);
  // Body 3 is the 0.7 kg ball; joint 0 the rigid pin, joint 2 the rope, 3 the rod.
  using J = nlohmann::json;
  const Broken table[] = {
      {"missing field",
       [](J& j) { j["joints"][0].erase("body_b"); },
       {},
       "/joints/0/body_b",
       "missing"},
      {"missing position",
       [](J& j) { j["bodies"][3].erase("position"); },
       {},
       "/bodies/3/position",
       "missing"},
      {"missing bodies", [](J& j) { j.erase("bodies"); }, {}, "/bodies", "missing"},
      {"wrong type",
       [](J& j) { j["bodies"][3]["mass"] = "heavy"; },
       {},
       "/bodies/3/mass",
       "= \"heavy\": expected a number"},
      {"wrong vector",
       [](J& j) {
         j["bodies"][3]["position"] = {1, 2};
       },
       {},
       "/bodies/3/position",
       "three numbers"},
      {"NaN", nullptr, {"\"mass\":0.7", "\"mass\":NaN"}, "/", "not valid JSON"},
      {"beyond double", nullptr, {"\"mass\":0.7", "\"mass\":1e999"}, "/", "1e999"},
      {"negative mass",
       [](J& j) { j["bodies"][3]["mass"] = -1.0; },
       {},
       "/bodies/3/mass",
       "= -1.0: softstep: create_body: BodyDef.mass = -1 rejected"},
      {"inertia not positive definite",
       [](J& j) {
         j["bodies"][3]["inertia"] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
       },
       {},
       "/bodies/3/inertia",
       "BodyDef.inertia"},
      {"unknown joint type",
       [](J& j) { j["joints"][0]["type"] = "hinge"; },
       {},
       "/joints/0/type",
       "= \"hinge\": unknown joint type (known: ball, distance"},
      {"bad body reference",
       [](J& j) { j["joints"][0]["body_b"] = 7; },
       {},
       "/joints/0/body_b",
       "= 7: no such body: the file has 4 bodies"},
      {"negative body reference",
       [](J& j) { j["joints"][0]["body_b"] = -1; },
       {},
       "/joints/0/body_b",
       "a body's index"},
      {"joint to itself",
       [](J& j) { j["joints"][0]["body_a"] = j["joints"][0]["body_b"]; },
       {},
       "/joints/0/body_b",
       "BallJointDef.body_b"},
      {"bad spring",
       [](J& j) { j["joints"][1]["spring"]["hertz"] = -2.0; },
       {},
       "/joints/1/spring/hertz",
       "= -2.0"},
      {"spring of the wrong kind",
       [](J& j) { j["joints"][1]["spring"] = "bouncy"; },
       {},
       "/joints/1/spring",
       "\"rigid\", \"free\""},
      {"min above max",
       [](J& j) { j["joints"][2]["min_length"] = 3.0; },
       {},
       "/joints/2/max_length",
       "DistanceJointDef.max_length"},
      {"misspelt field",
       [](J& j) { j["bodies"][3]["masss"] = 2.0; },
       {},
       "/bodies/3/masss",
       "unknown field"},
      // The fuzzer's find: "~" and "/" in a key are escaped in the path that quotes it.
      {"key with ~ and /",
       [](J& j) { j["bodies"][3]["m~a/ss"] = 2.0; },
       {},
       "/bodies/3/m~0a~1ss",
       "= 2.0: unknown field"},
      {"bad settings",
       [](J& j) { j["settings"]["substeps"] = 0; },
       {},
       "/settings/substeps",
       "WorldSettings.substeps"},
      {"fractional count",
       [](J& j) { j["settings"]["substeps"] = 2.5; },
       {},
       "/settings/substeps",
       "a whole number"},
      {"contact switch not a bool",
       [](J& j) { j["settings"]["contact"]["friction_while_solving"] = 1; },
       {},
       "/settings/contact/friction_while_solving",
       "expected true or false"},
      {"unknown contact setting",
       [](J& j) { j["settings"]["contact"]["friction_while_sliding"] = false; },
       {},
       "/settings/contact/friction_while_sliding",
       "unknown field"},
      {"unknown simd",
       [](J& j) { j["settings"]["simd"] = "avx1024"; },
       {},
       "/settings/simd",
       "= \"avx1024\""},
      {"unknown body type",
       [](J& j) { j["bodies"][0]["type"] = "ghost"; },
       {},
       "/bodies/0/type",
       "\"static\", \"kinematic\" or \"dynamic\""},
      {"newer version", [](J& j) { j["softstep_scene"] = 2; }, {}, "/softstep_scene", "version 1"},
      {"not an object", [](J& j) { j = J::array(); }, {}, "/", "expected an object"},
      {"truncated", nullptr, {"\"joints\"", "\"joints\": [{\"type\": \"ba"}, "/", "line"},
  };
  for (const Broken& b : table) {
    SCOPED_TRACE(b.what);
    std::string text = valid;
    if (b.edit) {
      J j = J::parse(valid);
      b.edit(j);
      text = j.dump();
    } else {
      text = replaced(valid, b.text_edit.first, b.text_edit.second);
      if (std::string(b.what) == "truncated") text = text.substr(0, text.find("\"ba") + 3);
    }
    try {
      load_scene_text(text, "my_scene.json");
      ADD_FAILURE() << "accepted";
    } catch (const SceneFileError& e) {
      EXPECT_EQ(e.field(), b.path) << e.what();
      EXPECT_EQ(e.file(), "my_scene.json");
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("my_scene.json: " + std::string(b.path), 0), 0) << message;
      EXPECT_NE(message.find(b.message), std::string::npos) << message;
    }
  }
}

TEST(SceneFile, AMissingFileIsNamed) {
  try {
    load_scene("/nonexistent/scene.json");
    ADD_FAILURE() << "accepted";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
  }
}

TEST(SceneFile, MissingOptionalFieldsTakeTheApiDefaults) {
  World world = load_scene_text(R"({"softstep_scene": 1,
      "bodies": [{"type": "static", "position": [0, 0, 0]},
                 {"type": "dynamic", "position": [0, -1, 0]}],
      "joints": [{"type": "distance", "body_a": 0, "body_b": 1}]})",
                                "minimal");
  const WorldSettings defaults;
  EXPECT_EQ(world.settings().substeps, defaults.substeps);
  EXPECT_EQ(world.settings().gravity, defaults.gravity);
  const BodyDef body_defaults;
  const BodyState b = world.body(world.body_ids()[1]);
  EXPECT_EQ(b.mass, body_defaults.mass);
  EXPECT_EQ(b.inertia, body_defaults.inertia);
  const DistanceJointDef d = world.distance_joint(world.joint_ids()[0]);
  EXPECT_EQ(d.rest_length, DistanceJointDef{}.rest_length);
  EXPECT_TRUE(std::isinf(d.max_length));
  EXPECT_TRUE(d.spring.is_rigid());
}

TEST(SceneFile, TheReadmeExampleLoads) {
  std::ifstream in(std::string(SOFTSTEP_SOURCE_DIR) + "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  const std::string text = readme.str();
  const std::size_t section = text.find("## Your own scene");
  ASSERT_NE(section, std::string::npos);
  const std::size_t begin = text.find("```json\n", section);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = text.find("```", begin + 8);
  World world = load_scene_text(text.substr(begin + 8, end - begin - 8), "README example");
  EXPECT_EQ(world.body_count(), 2u);
  EXPECT_EQ(world.joint_count(), 1u);
}

}  // namespace
}  // namespace softstep
