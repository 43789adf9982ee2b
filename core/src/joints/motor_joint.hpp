// The motor joint's kind (joint_kind.hpp); the kernel is simd/motor_joint_kernel.hpp.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/motor_joint_kernel.hpp"

namespace softstep {

struct MotorKind {
  using Def = MotorJointDef;
  static constexpr std::string_view def_name = "MotorJointDef";
  static constexpr JointType type = JointType::Motor;
  template <int W>
  using Group = simd::MotorJointGroup<W>;
  // point (3), rotation (3)
  static constexpr int kImpulses = 6;
  // One kernel: groups are packed by signature (each half rigid or soft).
  SOFTSTEP_SIGNATURE_KIND_PASSES(motor);
  static std::uint32_t signature(const JointSlot& j);
  static bool needs_solve(std::size_t, std::uint32_t) { return true; }
  static bool needs_relax(std::size_t, std::uint32_t signature);

  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies);

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
