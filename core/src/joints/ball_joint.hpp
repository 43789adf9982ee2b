// The ball joint's kind (joint_kind.hpp): the point part, rigid, soft or free.
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/ball_joint_kernel.hpp"

namespace softstep {

struct BallKind {
  using Def = BallJointDef;
  static constexpr std::string_view def_name = "BallJointDef";
  static constexpr JointType type = JointType::Ball;
  template <int W>
  using Group = simd::BallJointGroup<W>;
  static constexpr int kImpulses = 3;  // the point's, world frame
  // The general kernel and one variant per spring kind: the ball group's variant saves
  // little (README, "Only the effects a scene calls for"), but the free one drops every pass.
  static constexpr std::array variants{
      simd::kGeneralKernel,
      simd::JointFeatures{simd::RowKind::Rigid, false, false},
      simd::JointFeatures{simd::RowKind::Soft, false, false},
      simd::JointFeatures{simd::RowKind::Free, false, false},
  };
  static constexpr bool solves(std::size_t v) { return simd::ball_needs_solve(variants[v]); }
  static constexpr bool relaxes(std::size_t v) { return simd::ball_needs_relax(variants[v]); }

  template <class L, std::size_t V>
  static SOFTSTEP_INLINE void prepare(Group<simd::kWidth<L>>& g, const simd::BodyArrays&,
                                      const simd::SubstepContext& ctx, std::uint32_t) {
    simd::prepare_ball_joints<L, variants[V]>(g, ctx);
  }
  template <class L, std::size_t V>
  static SOFTSTEP_INLINE void warm_start(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                                         const simd::SubstepContext&, std::uint32_t) {
    simd::warm_start_ball_joints<L, variants[V]>(g, b);
  }
  template <class L, std::size_t V, bool kUseBias>
  static SOFTSTEP_INLINE void solve(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                                    const simd::SubstepContext&, std::uint32_t) {
    simd::solve_ball_joints<L, kUseBias, variants[V]>(g, b);
  }

  static std::uint8_t variant(const JointSlot& j, bool specialize);
  static std::uint32_t signature(const JointSlot&) { return 0; }
  static bool needs_solve(std::size_t v, std::uint32_t) { return solves(v); }
  static bool needs_relax(std::size_t v, std::uint32_t) { return relaxes(v); }

  template <int W>
  static void write_step_start(Group<W>&, int, JointSlot&, const BodySlots&) {}

  // The exact tree pass's impulse change (solver/tree_solver.hpp), world frame.
  template <int W>
  static void add_impulses(Group<W>& g, int lane, const float* delta) {
    for (int k = 0; k < 3; ++k) g.impulse[k][lane] += delta[k];
  }

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
