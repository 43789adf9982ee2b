// The weld joint's kind (joint_kind.hpp); the kernel is simd/weld_joint_kernel.hpp.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/weld_joint_kernel.hpp"

namespace softstep {

struct WeldKind {
  using Def = WeldJointDef;
  static constexpr std::string_view def_name = "WeldJointDef";
  static constexpr JointType type = JointType::Weld;
  template <int W>
  using Group = simd::WeldJointGroup<W>;
  // point (3), rotation lock (3)
  static constexpr int kImpulses = 6;
  // One kernel: groups are packed by signature (each half rigid, soft or free) and skip what
  // they lack.
  SOFTSTEP_SIGNATURE_KIND_PASSES(weld);
  static std::uint32_t signature(const JointSlot& j);
  static bool needs_solve(std::size_t, std::uint32_t signature);
  static bool needs_relax(std::size_t, std::uint32_t signature);

  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies);

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
