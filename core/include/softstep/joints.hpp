#pragma once

#include <Eigen/Core>
#include <limits>

#include "softstep/ids.hpp"
#include "softstep/spring.hpp"

namespace softstep {

// Keeps a point of body A and a point of body B together: 3 rows, rigid or soft (a soft
// ball joint is an isotropic spring of the given frequency in every direction).
struct BallJointDef {
  BodyId body_a;
  BodyId body_b;
  Eigen::Vector3d local_anchor_a = Eigen::Vector3d::Zero();  // m, body A frame, from its centre
  Eigen::Vector3d local_anchor_b = Eigen::Vector3d::Zero();  // m, body B frame
  Spring spring = Spring::rigid();
};

// Keeps the distance between two anchors at rest_length (rigid rod or spring), optionally
// bounded by [min_length, max_length]. A rope: Spring::free() and max_length = its length.
struct DistanceJointDef {
  BodyId body_a;
  BodyId body_b;
  Eigen::Vector3d local_anchor_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d local_anchor_b = Eigen::Vector3d::Zero();
  double rest_length = 1.0;  // m, >= 0; clamped into [min_length, max_length]
  double min_length = 0.0;   // m, >= 0; limit row only when > 0 and the spring is not rigid
  double max_length = std::numeric_limits<double>::infinity();  // m, >= min_length
  Spring spring = Spring::rigid();
};

// One value per registered joint type (core/src/joints/joint_registry.hpp).
enum class JointType { Ball, Distance, Revolute, Prismatic, Weld, SwingTwist, Wheel, Motor };
const char* joint_type_name(JointType type);  // "ball", "distance", "revolute", ...

// What a joint did in the last sub-step and how far it is from satisfied now.
struct JointReading {
  // Impulse applied to body B during the last sub-step by the linear rows, N s, world frame
  // (A got the opposite). Divided by the sub-step it is the joint force.
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N: impulse / sub-step
  // The same for the angular rows (angular locks, and a hinge's limit, motor and spring):
  // N m s and N m on B, world frame.
  Eigen::Vector3d angular_impulse = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  // Position error now, m: the anchor gap of a ball, revolute or weld joint; for a distance
  // joint, how far the length is outside [min, max], or from rest_length when rigid or
  // sprung; for a prismatic joint, the anchor's distance from the slide axis.
  double error = 0.0;
  // Orientation error now, rad: the angle between the hinge axes (revolute), the angle of
  // the relative rotation away from the held one (prismatic, weld), or how far the swing is
  // outside the cone or the twist outside its limit, the larger (swing-twist, 0 within).
  double angular_error = 0.0;
  // Revolute: the hinge angle, rad, unwrapped. Prismatic: the translation, m. Swing-twist:
  // the twist, rad, in (-pi, pi].
  double position = 0.0;
  // Swing-twist: the swing (the angle between the two twist axes), rad, in [0, pi].
  double swing = 0.0;
  // The axis rows' impulses in the last sub-step (revolute N m s, prismatic N s): the limit
  // rows' sum (lower pushes towards a larger position, upper towards a smaller one), the
  // motor, the spring. Swing-twist: the twist limit rows' sum, and the lengths of the
  // motor's and the spring's angular impulses.
  double limit_impulse = 0.0;
  double motor_impulse = 0.0;
  double spring_impulse = 0.0;
  // The effective mass m_eff = 1/K the joint's axis row sees now (the spring, motor and limit
  // row: what a Spring's hertz is relative to, and what a Spring::absolute's k and c act on),
  // from the poses and masses at the reading:
  //   revolute: about the hinge axis, kg m^2: 1 / (z.(I_a^-1 + I_b^-1) z)
  //   prismatic, wheel: along the slide (suspension) axis through B's anchor, kg:
  //     1 / (1/m_a + 1/m_b + the two bodies' rotation terms); 1/(1/m_a + 1/m_b) on the
  //     centres' line
  //   distance: along the line between the anchors, kg, the same form with each anchor's
  //     arm (NaN while the anchors coincide: no direction)
  // +infinity when neither body can move along the row. NaN for the joints whose springs
  // are 3-row blocks (ball, weld, swing-twist, motor joint): no one row to read.
  double effective_mass = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace softstep
