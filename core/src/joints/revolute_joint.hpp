// The revolute joint's kind (joint_kind.hpp); the kernel is simd/revolute_joint_kernel.hpp.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/revolute_joint_kernel.hpp"

namespace softstep {

struct RevoluteKind {
  using Def = RevoluteJointDef;
  static constexpr std::string_view def_name = "RevoluteJointDef";
  static constexpr JointType type = JointType::Revolute;
  template <int W>
  using Group = simd::RevoluteJointGroup<W>;
  // point (3), hinge lock (2), then the axis controls: lower, upper, motor, spring
  static constexpr int kImpulses = 9;
  // One kernel: groups are packed by signature (limit, motor, spring) and skip what they lack.
  SOFTSTEP_SIGNATURE_KIND_PASSES(revolute);
  static std::uint32_t signature(const JointSlot& j);
  static bool needs_solve(std::size_t, std::uint32_t) { return true; }
  static bool needs_relax(std::size_t, std::uint32_t) { return true; }

  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies);

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
