// softstep profile FILE.rec: a recording (World::start_recording, profile --record) replayed
// with profiling on, every step checked against the recording as `softstep replay` does, and
// reported like a scene: where the step time goes, per stage, over the recorded steps.
#pragma once

#include <string>

#include "tool/profile_command.hpp"

namespace softstep::tool {

int profile_recording(const ProfileOptions& options);

}  // namespace softstep::tool
