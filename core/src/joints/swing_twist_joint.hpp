// The swing-twist joint's kind (joint_kind.hpp); the kernel is
// simd/swing_twist_joint_kernel.hpp, the public definition softstep/joints/swing_twist.hpp.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/swing_twist_joint_kernel.hpp"

namespace softstep {

struct SwingTwistKind {
  using Def = SwingTwistJointDef;
  static constexpr std::string_view def_name = "SwingTwistJointDef";
  static constexpr JointType type = JointType::SwingTwist;
  template <int W>
  using Group = simd::SwingTwistJointGroup<W>;
  // point (3), swing (1), twist lower and upper (2), spring (3), motor (3)
  static constexpr int kImpulses = 12;
  // One kernel: groups are packed by signature (cone, twist limit, spring, motor) and skip
  // what they lack.
  SOFTSTEP_SIGNATURE_KIND_PASSES(swing_twist);
  static std::uint32_t signature(const JointSlot& j);
  static bool needs_solve(std::size_t, std::uint32_t) { return true; }
  static bool needs_relax(std::size_t, std::uint32_t) { return true; }

  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies);

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
