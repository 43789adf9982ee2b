#include "scenes/ragdoll_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "scenes/joint_at.hpp"

namespace softstep::scenes {

namespace {

constexpr double kPi = std::numbers::pi;

// A body part: its centre from the pelvis (T-pose, y up, facing +z), box size and mass.
struct Part {
  Eigen::Vector3d centre;
  Eigen::Vector3d size;  // m, full side lengths
  double mass;           // kg
};

// Pelvis, abdomen, chest, head; then left (-x) and right (+x) pairs: upper arm, forearm, hand,
// thigh, shin, foot. 16 parts, 72 kg.
std::vector<Part> parts() {
  std::vector<Part> p = {{{0.0, 0.0, 0.0}, {0.30, 0.20, 0.20}, 10.0},
                         {{0.0, 0.20, 0.0}, {0.28, 0.20, 0.18}, 7.0},
                         {{0.0, 0.45, 0.0}, {0.34, 0.30, 0.20}, 10.0},
                         {{0.0, 0.78, 0.0}, {0.18, 0.22, 0.20}, 4.0}};
  for (const double side : {-1.0, 1.0}) {
    p.push_back({{side * 0.35, 0.52, 0.0}, {0.26, 0.09, 0.09}, 2.0});
    p.push_back({{side * 0.62, 0.52, 0.0}, {0.26, 0.08, 0.08}, 1.5});
    p.push_back({{side * 0.83, 0.52, 0.0}, {0.14, 0.04, 0.09}, 0.5});
    p.push_back({{side * 0.10, -0.30, 0.0}, {0.13, 0.40, 0.13}, 7.0});
    p.push_back({{side * 0.10, -0.72, 0.0}, {0.10, 0.40, 0.10}, 4.0});
    p.push_back({{side * 0.10, -0.97, 0.06}, {0.10, 0.06, 0.24}, 1.0});
  }
  return p;
}

// Index of a part in parts(): the four of the trunk, then six per side.
enum : int { kPelvis, kAbdomen, kChest, kHead };
int limb(double side, int k) {  // k: 0 upper arm, 1 forearm, 2 hand, 3 thigh, 4 shin, 5 foot
  return 4 + (side < 0.0 ? 0 : 6) + k;
}

}  // namespace

RagdollScene build_ragdolls(World& world, const RagdollOptions& o) {
  if (o.count < 1) {
    throw std::invalid_argument("build_ragdolls: count must be >= 1 (got " +
                                std::to_string(o.count) + ")");
  }
  const std::vector<Part> shape = parts();
  const int side_count = static_cast<int>(std::ceil(std::sqrt(double(o.count))));
  RagdollScene scene;
  for (int n = 0; n < o.count; ++n) {
    const Eigen::Vector3d pelvis(2.0 * (n % side_count), o.height, 2.0 * (n / side_count));
    Ragdoll r;
    for (const Part& p : shape) {
      BodyDef d;
      d.position = pelvis + p.centre;
      d.mass = p.mass;
      d.inertia = solid_box_inertia(p.mass, p.size);
      d.linear_damping = o.limb_damping;
      d.angular_damping = o.limb_damping;
      r.bodies.push_back(world.create_body(d));
    }
    r.pelvis = r.bodies[kPelvis];
    const auto body = [&](int i) { return r.bodies[static_cast<std::size_t>(i)]; };
    // A swing-twist joint at `at` (from the pelvis) about `axis`, the twist axis along the
    // child; half_x leans towards the frame's reference (frames_at: the world axis least
    // aligned with `axis`), half_y towards axis x reference.
    const auto swing_twist = [&](int a, int b, const Eigen::Vector3d& at,
                                 const Eigen::Vector3d& axis, double half_x, double half_y,
                                 double twist) {
      auto j = joint_at<SwingTwistJointDef>(world, body(a), body(b), pelvis + at, axis);
      j.cone = {true, half_x, half_y};
      j.twist = {true, -twist, twist};
      j.motor = {o.friction > 0.0, o.friction};
      r.swing_twists.push_back(world.create_joint(j));
    };
    const auto hinge = [&](int a, int b, const Eigen::Vector3d& at, const Eigen::Vector3d& axis,
                           double lower, double upper) {
      auto j = joint_at<RevoluteJointDef>(world, body(a), body(b), pelvis + at, axis);
      j.limit = {true, lower, upper};
      j.motor = {o.friction > 0.0, 0.0, 0.5 * o.friction};  // speed 0: friction
      r.hinges.push_back(world.create_joint(j));
    };
    const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    // Spine and neck, twist axis up; reference x: half_x bends sideways, half_y back/forth.
    swing_twist(kPelvis, kAbdomen, {0.0, 0.10, 0.0}, up, 0.30, 0.50, 0.30);
    swing_twist(kAbdomen, kChest, {0.0, 0.30, 0.0}, up, 0.30, 0.50, 0.30);
    swing_twist(kChest, kHead, {0.0, 0.64, 0.0}, up, 0.50, 0.70, 1.00);
    for (const double side : {-1.0, 1.0}) {
      const Eigen::Vector3d out(side, 0.0, 0.0);
      // Shoulder and wrist, twist axis along the arm; reference y: half_x up and down.
      swing_twist(kChest, limb(side, 0), {side * 0.22, 0.52, 0.0}, out, 1.30, 1.00, 1.00);
      // Elbow: the forearm bends forwards (+z) by a positive angle, 0 to 145 degrees.
      hinge(limb(side, 0), limb(side, 1), {side * 0.48, 0.52, 0.0}, -side * up, 0.0, 2.53);
      swing_twist(limb(side, 1), limb(side, 2), {side * 0.76, 0.52, 0.0}, out, 1.00, 0.50, 0.20);
      // Hip, twist axis down the leg; reference x: half_x sideways, half_y forwards/back.
      swing_twist(kPelvis, limb(side, 3), {side * 0.10, -0.10, 0.0}, -up, 0.60, 1.20, 0.50);
      // Knee: the shin bends backwards (-z) by a positive angle, 0 to 140 degrees; ankle.
      hinge(limb(side, 3), limb(side, 4), {side * 0.10, -0.50, 0.0}, Eigen::Vector3d::UnitX(), 0.0,
            2.44);
      hinge(limb(side, 4), limb(side, 5), {side * 0.10, -0.92, 0.0}, Eigen::Vector3d::UnitX(),
            -0.70, 0.50);
    }
    // The rope: from a hook just above the pelvis, slack by rope_length.
    BodyDef hook;
    hook.type = BodyType::Static;
    hook.position = pelvis + Eigen::Vector3d(0.0, 0.10, 0.0);
    const BodyId hook_id = world.create_body(hook);
    DistanceJointDef rope;
    rope.body_a = hook_id;
    rope.body_b = r.pelvis;
    rope.local_anchor_b = {0.0, 0.10, 0.0};
    rope.spring = Spring::free();
    rope.rest_length = o.rope_length;
    rope.max_length = o.rope_length;
    scene.hooks.push_back(hook_id);
    scene.ropes.push_back(world.create_joint(rope));
    scene.ragdolls.push_back(std::move(r));
  }
  return scene;
}

RagdollLimits ragdoll_limit_violation(const World& world, const RagdollScene& scene) {
  RagdollLimits worst;
  constexpr double kDegrees = 180.0 / kPi;
  for (const Ragdoll& r : scene.ragdolls) {
    for (JointId j : r.swing_twists) {
      worst.swing_twist_degrees =
          std::max(worst.swing_twist_degrees, world.joint_reading(j).angular_error * kDegrees);
    }
    for (JointId j : r.hinges) {
      const AxisLimit limit = world.joint_def<RevoluteJointDef>(j).limit;
      const double angle = world.joint_reading(j).position;
      const double outside = std::max({0.0, limit.lower - angle, angle - limit.upper});
      worst.hinge_degrees = std::max(worst.hinge_degrees, outside * kDegrees);
    }
  }
  return worst;
}

}  // namespace softstep::scenes
