// Weld joint: holds B's anchor on A's and B's frame turned as A's: 3 angular rows, then the
// point (3 linear rows). Each half is rigid or soft. A soft angular half is the talk's
// "Buddha spring" for orientation: a torsion spring of the given frequency about every axis,
// felt by the effective inertia the rows see; a soft linear half is an isotropic spring.
// Free halves run no rows (a free angular half leaves a ball joint).
#pragma once

#include "softstep/ids.hpp"
#include "softstep/joints/joint_frames.hpp"
#include "softstep/spring.hpp"

namespace softstep {

struct WeldJointDef {
  BodyId body_a;
  BodyId body_b;
  JointFrame frame_a;  // the anchor and orientation held, in A's frame
  JointFrame frame_b;
  Spring linear = Spring::rigid();
  Spring angular = Spring::rigid();
};

}  // namespace softstep
