// The wheel joint's kind (joint_kind.hpp); the kernel is simd/wheel_joint_kernel.hpp.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/wheel_joint_kernel.hpp"

namespace softstep {

struct WheelKind {
  using Def = WheelJointDef;
  static constexpr std::string_view def_name = "WheelJointDef";
  static constexpr JointType type = JointType::Wheel;
  template <int W>
  using Group = simd::WheelJointGroup<W>;
  // lateral lock (2), axle lock (2), one unused, then the axis controls at kAxisImpulses:
  // lower, upper (travel limits), motor (the spin motor), spring (the suspension)
  static constexpr int kImpulses = 9;
  // A slider: the linear rows act on A at B's anchor, which runs along A's axis, so A's lever
  // for the geometric inertia runs from A's centre to B's anchor (lane_solver.cpp).
  static constexpr bool kActsOnAAtAnchorB = true;
  // One kernel: groups are packed by signature (limits, spin motor, spring) and skip what
  // they lack.
  SOFTSTEP_SIGNATURE_KIND_PASSES(wheel);
  static std::uint32_t signature(const JointSlot& j);
  static bool needs_solve(std::size_t, std::uint32_t) { return true; }
  static bool needs_relax(std::size_t, std::uint32_t) { return true; }

  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j, const BodySlots& bodies);

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
