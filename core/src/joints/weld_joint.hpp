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
  static constexpr std::array<int, 1> variants{0};
  static constexpr bool solves(std::size_t) { return true; }
  static constexpr bool relaxes(std::size_t) { return true; }

  template <class L, std::size_t>
  static void prepare(Group<simd::kWidth<L>>& g, const simd::BodyArrays&,
                      const simd::SubstepContext& ctx, std::uint32_t signature) {
    simd::prepare_weld_joints<L>(g, ctx, signature);
  }
  template <class L, std::size_t>
  static void warm_start(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                         const simd::SubstepContext&, std::uint32_t signature) {
    simd::warm_start_weld_joints<L>(g, b, signature);
  }
  template <class L, std::size_t, bool kUseBias>
  static void solve(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                    const simd::SubstepContext& ctx, std::uint32_t signature) {
    simd::solve_weld_joints<L, kUseBias>(g, b, ctx, signature);
  }

  static std::uint8_t variant(const JointSlot&, bool) { return 0; }
  static std::uint32_t signature(const JointSlot& j);
  static int rows(std::size_t v, std::uint32_t signature);
  static bool needs_solve(std::size_t, std::uint32_t signature);
  static bool needs_relax(std::size_t, std::uint32_t signature);
  static PlanKernel plan_kernel(std::size_t v, std::uint32_t signature);
  static JointEffects effects(const JointSlot& j);
  static double tension(const JointSlot& j, const float* impulse);

  template <int W>
  static void fill_lane(Group<W>& g, int lane, const JointSlot& j);
  template <int W>
  static void write_step_start(Group<W>& g, int lane, JointSlot& j,
                               const std::vector<BodySlot>& bodies);
  template <int W>
  static void read_impulses(const Group<W>& g, int lane, float* out);
  template <int W>
  static void clear_impulses(Group<W>& g);

  static JointSlot make_slot(const World::Impl& w, std::string_view call, const Def& def);
  static Def def_of(const World::Impl& w, const JointSlot& j);
  static void reading(const World::Impl& w, const JointSlot& j, const float* impulse,
                      JointReading& r);
  static void hash(StateHasher& h, const JointSlot& j);
};

}  // namespace softstep
