// The generic joint calls of World (create_joint, joint_def, set_joint), defined once here and
// instantiated in each kind's .cpp with SOFTSTEP_INSTANTIATE_JOINT_API.
#pragma once

#include "joints/joint_registry.hpp"
#include "validation.hpp"
#include "world_impl.hpp"

namespace softstep {

// The kind whose Def is D.
template <class D>
struct KindOfDef {
  template <class... Kinds>
  struct Find {
    using type = void;
  };
  template <class K, class... Rest>
  struct Find<K, Rest...> {
    using type =
        std::conditional_t<std::is_same_v<typename K::Def, D>, K, typename Find<Rest...>::type>;
  };
  template <class... Kinds>
  using In = typename Find<Kinds...>::type;
  using type = JointKinds::Expand<In>;
};
template <class D>
using KindOf = typename KindOfDef<D>::type;

// Adds a validated slot (world.cpp): ids, islands, colouring.
JointId add_joint(World::Impl& w, JointSlot&& joint);
// The slot of a live joint of kind `type`, or InvalidArgument naming what it is instead.
const JointSlot& joint_of_type(const World::Impl& w, std::string_view call, JointId id,
                               JointType type);
// Reports a created joint (its finished id) to a running recording (world.cpp).
void record_created_joint(const World& world, World::Impl& w, JointId id);
// Reports a joint changed by set_joint to a running recording (world.cpp).
void record_set_joint(const World& world, World::Impl& w, JointId id);
// Replaces a joint's settings in place (world.cpp): keeps id, bodies and impulses.
void replace_joint(World::Impl& w, std::uint32_t slot, JointSlot&& joint);

// Every joint type is created here: validated, added, then recorded with its finished id.
template <class Def>
JointId create_joint_of(const World& world, World::Impl& w, std::string_view call,
                        const Def& def) {
  const JointId id = add_joint(w, KindOf<Def>::make_slot(w, call, def));
  record_created_joint(world, w, id);
  return id;
}

template <class Def>
JointId World::create_joint(const Def& def) {
  return create_joint_of(*this, *impl_, "create_joint", def);
}

template <class Def>
Def World::joint_def(JointId id) const {
  using K = KindOf<Def>;
  return K::def_of(*impl_, joint_of_type(*impl_, "joint_def", id, K::type));
}

template <class Def>
void World::set_joint(JointId id, const Def& def) {
  using K = KindOf<Def>;
  const JointSlot& old = joint_of_type(*impl_, "set_joint", id, K::type);
  JointSlot next = K::make_slot(*impl_, "set_joint", def);
  if (next.body_a != old.body_a || next.body_b != old.body_b) {
    const bool a_changed = next.body_a != old.body_a;
    const BodyId given = a_changed ? def.body_a : def.body_b;
    validation::reject("set_joint", std::string(K::def_name) + (a_changed ? ".body_a" : ".body_b"),
                       "BodyId{" + std::to_string(given.index) + "}",
                       "a joint keeps its bodies (destroy it and create another)");
  }
  replace_joint(*impl_, id.index, std::move(next));
  record_set_joint(*this, *impl_, id);
}

}  // namespace softstep

#define SOFTSTEP_INSTANTIATE_JOINT_API(DEF)              \
  template JointId World::create_joint<DEF>(const DEF&); \
  template DEF World::joint_def<DEF>(JointId) const;     \
  template void World::set_joint<DEF>(JointId, const DEF&);
