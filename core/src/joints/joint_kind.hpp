// What a joint type is to the world and the solver: a "kind", a struct of static members that
// every registered type provides (the contract is written out below, BallKind in
// ball_joint.hpp is the simplest example). The solver's loops, the world's joint lifecycle,
// the plan and the state hash iterate over the registry (joint_registry.hpp) and never name
// a type: a new type is its kernel header (simd/), its public header, its kind (.hpp + .cpp
// here) and one line in the registry.
//
// The contract, for a kind K:
//   using Def;                              the public definition (RevoluteJointDef, ...)
//   static constexpr JointType type;
//   template <int W> using Group;           its lane group (SoA over W lanes, an AnchorLanes first)
//   static constexpr int kImpulses;         floats of accumulated impulse one joint keeps
//   static constexpr std::array variants;   compiled kernel variants, [0] the general kernel
//   static constexpr bool solves(v), relaxes(v)      whether variant v has those passes at all
//   template <class L, std::size_t V> prepare / warm_start, template <.., bool kUseBias> solve:
//                                           one group's pass, for kind_kernels.hpp to loop over
//   variant(slot, specialize), signature(slot): the run a joint is packed in. A signature is a
//                                           bit set of the parts a joint runs; runs are uniform
//                                           in it, so kernels branch on it once per group
//   rows(v, sig), needs_solve(v, sig), needs_relax(v, sig), plan_kernel(v, sig)
//   effects(slot), tension(slot, impulse)
//   template <int W> fill_lane / write_step_start / read_impulses / clear_impulses
//   make_slot(world, call, def) (validates), def_of(world, slot), reading(...), hash(...)
// The members defined out of line are declared by SOFTSTEP_JOINT_KIND_MEMBERS, and a kind with
// one signature-packed kernel gets its variants and passes from SOFTSTEP_SIGNATURE_KIND_PASSES
// (both at the end of this file; RevoluteKind uses both).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "slot_vectors.hpp"
#include "softstep/simd/step_context.hpp"
#include "softstep/step_plan.hpp"
#include "softstep/world.hpp"

namespace softstep {

class StateHasher;

// The most impulse floats any type keeps (a revolute joint with every part: 3 point, 2 lock,
// limit lower and upper, motor, spring).
inline constexpr int kMaxJointImpulses = 12;

// The effects a joint brings into a step (StepPlan).
struct JointEffects {
  bool springs = false;
  bool limits = false;
  bool motors = false;
};

template <class... Kinds>
struct KindList {
  static constexpr std::size_t size = sizeof...(Kinds);
  // Calls f.template operator()<Kind>() for each kind, in registry order.
  template <class F>
  static void for_each(F&& f) {
    (f.template operator()<Kinds>(), ...);
  }
  // f.template operator()<Kind>() for the kind of `type`.
  template <class F>
  static decltype(auto) with(JointType type, F&& f) {
    using R = decltype(f.template operator()<First>());
    if constexpr (std::is_void_v<R>) {
      (void)((Kinds::type == type ? (f.template operator()<Kinds>(), true) : false) || ...);
    } else {
      R result{};
      (void)((Kinds::type == type ? (result = f.template operator()<Kinds>(), true) : false) ||
             ...);
      return result;
    }
  }
  template <template <class> class T>
  using Apply = std::tuple<T<Kinds>...>;
  // The position of K in the list (its element in an Apply tuple).
  template <class K>
  static constexpr std::size_t index_of() {
    std::size_t i = 0, found = sizeof...(Kinds);
    ((std::is_same_v<K, Kinds> ? (found = i, ++i) : ++i), ...);
    return found;
  }
  template <template <class...> class T>
  using Expand = T<Kinds...>;

 private:
  template <class K, class...>
  struct Head {
    using type = K;
  };
  using First = typename Head<Kinds...>::type;
};

// One pass of one variant over `count` consecutive groups; nullptr where the variant has no
// such pass (the plan does not schedule it).
template <class Group>
using PassFn = void (*)(Group*, std::size_t count, const simd::BodyArrays&,
                        const simd::SubstepContext&, std::uint32_t signature);

template <class Group>
struct PassKernels {
  PassFn<Group> prepare = nullptr;
  PassFn<Group> warm_start = nullptr;
  PassFn<Group> solve = nullptr;
  PassFn<Group> relax = nullptr;
};

// The kernels of one kind at width W: one PassKernels per variant.
template <class Kind, int W>
using KindKernels =
    std::array<PassKernels<typename Kind::template Group<W>>, Kind::variants.size()>;

// Defined in the generated <kind>_kernels_<width>.cpp (kind_kernels.hpp builds it).
template <class Kind, int W>
KindKernels<Kind, W> kind_kernels();

// The contract's members that every kind defines out of line in its .cpp, declared once here;
// a kind's struct says `SOFTSTEP_JOINT_KIND_MEMBERS;` after its Def and Group aliases.
#define SOFTSTEP_JOINT_KIND_MEMBERS                                                        \
  static int rows(std::size_t v, std::uint32_t signature);                                 \
  static PlanKernel plan_kernel(std::size_t v, std::uint32_t signature);                   \
  static JointEffects effects(const JointSlot& j);                                         \
  static double tension(const JointSlot& j, const float* impulse);                         \
  template <int W>                                                                         \
  static void fill_lane(Group<W>& g, int lane, const JointSlot& j);                        \
  template <int W>                                                                         \
  static void read_impulses(const Group<W>& g, int lane, float* out);                      \
  template <int W>                                                                         \
  static void clear_impulses(Group<W>& g);                                                 \
  static JointSlot make_slot(const World::Impl& w, std::string_view call, const Def& def); \
  static Def def_of(const World::Impl& w, const JointSlot& j);                             \
  static void reading(const World::Impl& w, const JointSlot& j, const float* impulse,      \
                      JointReading& r);                                                    \
  static void hash(StateHasher& h, const JointSlot& j)

// A kind with one kernel whose runs are packed by signature (the parts a joint has), so the
// kernel branches on the signature once per group instead of being compiled per variant. Its
// passes are simd::prepare_<name>_joints<L>(g, ctx, sig), warm_start_<name>_joints<L>(g, b, sig)
// and solve_<name>_joints<L, kUseBias>(g, b, ctx, sig).
#define SOFTSTEP_SIGNATURE_KIND_PASSES(name)                                                      \
  static constexpr std::array<int, 1> variants{0};                                                \
  static constexpr bool solves(std::size_t) {                                                     \
    return true;                                                                                  \
  }                                                                                               \
  static constexpr bool relaxes(std::size_t) {                                                    \
    return true;                                                                                  \
  }                                                                                               \
  static std::uint8_t variant(const JointSlot&, bool) {                                           \
    return 0;                                                                                     \
  }                                                                                               \
  template <class L, std::size_t>                                                                 \
  static SOFTSTEP_INLINE void prepare(Group<simd::kWidth<L>>& g, const simd::BodyArrays&,         \
                                      const simd::SubstepContext& ctx, std::uint32_t signature) { \
    simd::prepare_##name##_joints<L>(g, ctx, signature);                                          \
  }                                                                                               \
  template <class L, std::size_t>                                                                 \
  static SOFTSTEP_INLINE void warm_start(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,    \
                                         const simd::SubstepContext&, std::uint32_t signature) {  \
    simd::warm_start_##name##_joints<L>(g, b, signature);                                         \
  }                                                                                               \
  template <class L, std::size_t, bool kUseBias>                                                  \
  static SOFTSTEP_INLINE void solve(Group<simd::kWidth<L>>& g, const simd::BodyArrays& b,         \
                                    const simd::SubstepContext& ctx, std::uint32_t signature) {   \
    simd::solve_##name##_joints<L, kUseBias>(g, b, ctx, signature);                               \
  }                                                                                               \
  static_assert(true, "")

}  // namespace softstep
