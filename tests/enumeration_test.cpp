// Walking the world's bodies and joints, and the caller's value kept with each (issue 17,
// hook 10): ids come back in slot order exactly as create_* gave them, destroyed ones are
// gone, and user data changes neither the simulation nor the state hash.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep {
namespace {

struct Scene {
  World world;
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
};

// A ground and a 5-link chain; link 2 and the joint holding link 3 are destroyed, which also
// destroys the joints on link 2.
void build(Scene& s) {
  BodyDef ground;
  ground.type = BodyType::Static;
  s.bodies.push_back(s.world.create_body(ground));
  for (int i = 1; i <= 5; ++i) {
    BodyDef link;
    link.position = {0.25 * i, 0.0, 0.0};
    s.bodies.push_back(s.world.create_body(link));
    BallJointDef j;
    j.body_a = s.bodies[static_cast<std::size_t>(i - 1)];
    j.body_b = s.bodies.back();
    j.local_anchor_b = {-0.25, 0.0, 0.0};
    s.joints.push_back(s.world.create_ball_joint(j));
  }
}

TEST(Enumeration, ListsLiveBodiesAndJointsInSlotOrder) {
  Scene s;
  build(s);
  EXPECT_EQ(s.world.body_ids(), s.bodies);
  EXPECT_EQ(s.world.joint_ids(), s.joints);

  s.world.destroy_body(s.bodies[2]);  // and the joints 1 (1-2) and 2 (2-3)
  const std::vector<BodyId> bodies{s.bodies[0], s.bodies[1], s.bodies[3], s.bodies[4], s.bodies[5]};
  const std::vector<JointId> joints{s.joints[0], s.joints[3], s.joints[4]};
  EXPECT_EQ(s.world.body_ids(), bodies);
  EXPECT_EQ(s.world.joint_ids(), joints);
  EXPECT_EQ(s.world.body_ids().size(), s.world.body_count());
  EXPECT_EQ(s.world.joint_ids().size(), s.world.joint_count());
}

TEST(Enumeration, UserDataIsKeptButNeverSimulatedOrHashed) {
  Scene plain, tagged;
  build(plain);
  build(tagged);
  int engine_object = 0;
  const auto pointer = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&engine_object));
  const std::uint64_t before = tagged.world.state_hash();
  tagged.world.set_user_data(tagged.bodies[3], pointer);
  tagged.world.set_user_data(tagged.joints[4], 42);
  EXPECT_EQ(tagged.world.state_hash(), before);
  for (int i = 0; i < 30; ++i) {
    plain.world.step(1.0 / 60.0);
    tagged.world.step(1.0 / 60.0);
  }
  EXPECT_EQ(tagged.world.state_hash(), plain.world.state_hash());
  EXPECT_EQ(tagged.world.user_data(tagged.bodies[3]), pointer);
  EXPECT_EQ(
      reinterpret_cast<int*>(static_cast<std::uintptr_t>(tagged.world.user_data(tagged.bodies[3]))),
      &engine_object);
  EXPECT_EQ(tagged.world.user_data(tagged.joints[4]), 42u);
  EXPECT_EQ(tagged.world.user_data(tagged.bodies[1]), 0u);  // never set
  EXPECT_EQ(tagged.world.user_data(tagged.joints[0]), 0u);

  // From the definition; a reused slot starts from the new definition's value.
  BodyDef def;
  def.user_data = 7;
  const BodyId made = tagged.world.create_body(def);
  EXPECT_EQ(tagged.world.user_data(made), 7u);
  tagged.world.destroy_body(made);
  const BodyId reused = tagged.world.create_body(BodyDef{});
  EXPECT_EQ(reused.index, made.index);
  EXPECT_EQ(tagged.world.user_data(reused), 0u);

  // Stale ids are rejected like everywhere else.
  EXPECT_THROW(tagged.world.user_data(made), InvalidArgument);
  EXPECT_THROW(tagged.world.set_user_data(made, 1), InvalidArgument);
  tagged.world.destroy_joint(tagged.joints[4]);
  EXPECT_THROW(tagged.world.user_data(tagged.joints[4]), InvalidArgument);
}

}  // namespace
}  // namespace softstep
