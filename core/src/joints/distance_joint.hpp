// The distance joint's kind (joint_kind.hpp): a spring or rod row and two limit rows along
// the anchors' axis (axis parts).
#pragma once

#include "joints/joint_kind.hpp"
#include "softstep/simd/distance_joint_kernel.hpp"

namespace softstep {

struct DistanceKind {
  using Def = DistanceJointDef;
  static constexpr std::string_view def_name = "DistanceJointDef";
  static constexpr JointType type = JointType::Distance;
  template <int W>
  using Group = simd::DistanceJointGroup<W>;
  static constexpr int kImpulses = 3;  // spring or rod, lower limit, upper limit (along n)
  // The general kernel evaluates both limit rows for every lane: the variants that leave out
  // the rows a group lacks save 30-40 % (README, "Only the effects a scene calls for").
  static constexpr std::array variants{
      simd::kGeneralKernel,
      simd::JointFeatures{simd::RowKind::Rigid, false, false},  // a rod has no limit rows
      simd::JointFeatures{simd::RowKind::Soft, false, false},
      simd::JointFeatures{simd::RowKind::Soft, true, false},
      simd::JointFeatures{simd::RowKind::Soft, false, true},
      simd::JointFeatures{simd::RowKind::Soft, true, true},
      simd::JointFeatures{simd::RowKind::Free, false, false},
      simd::JointFeatures{simd::RowKind::Free, true, false},
      simd::JointFeatures{simd::RowKind::Free, false, true},
      simd::JointFeatures{simd::RowKind::Free, true, true},
  };
  static constexpr bool solves(std::size_t v) { return simd::distance_needs_solve(variants[v]); }
  static constexpr bool relaxes(std::size_t v) { return simd::distance_needs_relax(variants[v]); }

  template <class L, std::size_t V>
  static SOFTSTEP_INLINE void prepare(Group<simd::kWidth<L>>& g, const simd::BodyArrays&,
                                      const simd::SubstepContext& ctx, std::uint32_t) {
    simd::prepare_distance_joints<L, variants[V]>(g, ctx);
  }
  template <class L, std::size_t V>
  static SOFTSTEP_INLINE void warm_start(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                                         const simd::SubstepContext&, std::uint32_t) {
    simd::warm_start_distance_joints<L, variants[V]>(g, b);
  }
  template <class L, std::size_t V, bool kUseBias>
  static SOFTSTEP_INLINE void solve(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,
                                    const simd::SubstepContext& ctx, std::uint32_t) {
    simd::solve_distance_joints<L, kUseBias, variants[V]>(g, b, ctx);
  }

  static std::uint8_t variant(const JointSlot& j, bool specialize);
  static std::uint32_t signature(const JointSlot&) { return 0; }
  static bool needs_solve(std::size_t v, std::uint32_t) { return solves(v); }
  static bool needs_relax(std::size_t v, std::uint32_t) { return relaxes(v); }

  template <int W>
  static void write_step_start(Group<W>&, int, JointSlot&, const BodySlots&) {}

  // The exact tree pass's impulse change along the axis (solver/tree_solver.hpp): the rod row.
  template <int W>
  static void add_impulses(Group<W>& g, int lane, const float* delta) {
    g.impulse[lane] += delta[0];
  }

  SOFTSTEP_JOINT_KIND_MEMBERS;
};

}  // namespace softstep
