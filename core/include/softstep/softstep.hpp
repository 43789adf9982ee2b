// softstep: soft-constraint rigid-body solver. Include this one header.
#pragma once

#include "softstep/body.hpp"
#include "softstep/contacts.hpp"
#include "softstep/errors.hpp"
#include "softstep/ids.hpp"
#include "softstep/joints.hpp"
#include "softstep/joints/prismatic.hpp"
#include "softstep/joints/revolute.hpp"
#include "softstep/joints/swing_twist.hpp"
#include "softstep/joints/weld.hpp"
#include "softstep/profile.hpp"
#include "softstep/recording.hpp"
#include "softstep/scene_file.hpp"
#include "softstep/spring.hpp"
#include "softstep/step_plan.hpp"
#include "softstep/world.hpp"
#include "softstep/world_settings.hpp"
