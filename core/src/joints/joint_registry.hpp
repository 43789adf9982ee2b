// THE list of joint types. Order matters only for layout: within a colour, and in the overflow
// set (solved in order), joints are grouped by kind in this order, so a new kind goes last.
// core/CMakeLists.txt reads this list to generate each kind's kernel files (one per width).
#pragma once

#include <variant>

#include "joints/ball_joint.hpp"
#include "joints/distance_joint.hpp"
#include "joints/prismatic_joint.hpp"
#include "joints/revolute_joint.hpp"
#include "joints/swing_twist_joint.hpp"
#include "joints/weld_joint.hpp"
#include "joints/wheel_joint.hpp"
#include "joints/motor_joint.hpp"

namespace softstep {

// clang-format off
using JointKinds = KindList<
    BallKind,
    DistanceKind,
    RevoluteKind,
    PrismaticKind,
    WeldKind,
    SwingTwistKind,
    WheelKind,
    MotorKind>;
// clang-format on

template <class... Kinds>
using DefVariant = std::variant<typename Kinds::Def...>;
// Every type's definition: what a joint slot holds (as validated, in double).
using JointDefs = JointKinds::Expand<DefVariant>;

}  // namespace softstep
