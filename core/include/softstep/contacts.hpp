// Contacts from the caller's collision detection (README, "Contacts").
//
// Each step the caller hands World::step the contact manifolds its narrow phase found for the
// poses the world has now; softstep solves them as soft contacts (Soft Step) in the same
// coloured SIMD lanes as the joints and reports what it applied (World::contact_readings).
//
// Why the contacts are an argument of step() and not a member set before it: a manifold is
// true only for the poses it was computed at, so it belongs to exactly one step. Passing the
// span to step() makes that lifetime the call's: nothing stale can be solved a second time, the
// caller's storage is read only during the call (the world copies what it keeps, for warm
// starting), and a step without contacts is simply step(dt).
//
// Conventions
// - Units: metres, seconds, kilograms; impulses in N s.
// - The normal is a world-frame unit vector pointing from body A to body B: pushing B along
//   +normal separates the pair.
// - A point is where the two surfaces touch (or nearly touch): anchor_a and anchor_b are the
//   closest features of A and B in each body's own frame (relative to its centre of mass, as
//   joint anchors are). separation is their distance along the normal, negative when the
//   shapes overlap (penetration), positive for a speculative point that is still apart: such a
//   point lets the gap close within the step but pushes only if the bodies would pass through.
//   World::local_point converts world points to anchors.
// - Round shapes (spheres, capsules, wheels, rounded boxes) set radius_a / radius_b: a body's
//   anchors are then points of its shape's core (a sphere's centre, the closest point of a
//   capsule's segment) and its surface lies that radius further along the normal (A's surface
//   at core_a + radius_a * normal, B's at core_b - radius_b * normal). separation stays the
//   distance between the surfaces. Why: within a step softstep follows each point by turning
//   its anchors with the body; a rolling wheel's surface point turns away from the ground
//   (by r (1 - cos) per step, centimetres at road speeds) although the wheel does not rise,
//   while its centre turns with it and stays put. Leave both 0 for flat features (box corners
//   and faces); the results are then bit for bit those of a manifold without radii.
// - feature_id identifies a point within its manifold from step to step (e.g. the pair of
//   features of the two shapes that produced it); key identifies the manifold within its body
//   pair (e.g. the two shapes' ids when bodies have several shapes). A point whose (ordered
//   body pair, key, feature_id) was in the previous step starts from that step's impulses
//   (warm starting); otherwise it starts from zero and reads as new.
// - Matching is by content, not by position in the span; results still depend on the order in
//   which manifolds are given (it decides the solve order), so give them in a deterministic
//   order for reproducible runs.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "softstep/ids.hpp"

namespace softstep {

inline constexpr int kMaxContactPoints = 4;

struct ContactPoint {
  Eigen::Vector3d anchor_a = Eigen::Vector3d::Zero();  // body A frame, m from its centre
  Eigen::Vector3d anchor_b = Eigen::Vector3d::Zero();  // body B frame, m from its centre
  double separation = 0.0;  // m along the normal; negative = penetration
  std::uint32_t feature_id = 0;
};

struct ContactManifold {
  BodyId body_a;
  BodyId body_b;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // world, unit, from A to B
  int point_count = 0;                                // 1 .. kMaxContactPoints
  std::array<ContactPoint, kMaxContactPoints> points{};
  // Coulomb friction coefficient, >= 0 (0: no friction rows at all). The friction cone is
  // approximated per point by a disk: the two tangent impulses together are capped by
  // friction * that point's normal impulse.
  double friction = 0.6;
  double restitution = 0.0;         // in [0, 1]: bounce speed / impact speed
  double rolling_resistance = 0.0;  // m, >= 0: angular impulse cap = this * total normal impulse
  // Desired speed of B's surface relative to A's along the two tangent directions (a conveyor
  // belt), m/s. The tangents are tangent_directions(normal).
  Eigen::Vector2d tangent_speed = Eigen::Vector2d::Zero();
  std::uint64_t key = 0;  // the caller's id of this manifold within its body pair
  // m, finite, >= 0: the shape's radius about its anchors when they are a round shape's core
  // (see "Round shapes" above); 0 = the anchors are on the surface.
  double radius_a = 0.0;
  double radius_b = 0.0;
};

// The two world tangents softstep uses for a normal (unit, orthogonal, right-handed with the
// normal: t1 x t2 = normal). Deterministic: the same normal gives the same tangents.
std::array<Eigen::Vector3d, 2> tangent_directions(const Eigen::Vector3d& normal);

// What the last step applied at one point, N s, impulses of its last sub-step (the force is
// impulse * substeps / dt).
struct ContactPointReading {
  double normal_impulse = 0.0;                                 // >= 0, on B along +normal
  Eigen::Vector3d friction_impulse = Eigen::Vector3d::Zero();  // on B, world, in the tangent plane
  double max_normal_impulse = 0.0;  // the largest normal impulse over the step's sub-steps
  bool is_new = true;               // no matching point in the previous step
};

struct ContactReading {
  BodyId body_a;
  BodyId body_b;
  int point_count = 0;
  std::array<ContactPointReading, kMaxContactPoints> points{};
  // Angular impulse of the rolling resistance on B, world, N m s (twist about the normal
  // included); zero without rolling resistance.
  Eigen::Vector3d rolling_impulse = Eigen::Vector3d::Zero();
};

// WorldSettings::contact: how contacts are solved (the talk's soft contact).
struct ContactSettings {
  // The contact spring while solving: a penetration is pushed out like a spring of this
  // frequency and damping ratio (relative to the pair's effective mass), Hz > 0 and >= 0.
  double hertz = 30.0;
  double damping_ratio = 10.0;
  double max_push_out_speed = 3.0;  // m/s, > 0: the spring never pushes apart faster
  // Restitution applies only when the pair closes faster than this, m/s, >= 0 (slow contacts
  // come to rest instead of jittering).
  double restitution_threshold = 1.0;
  // Friction rows in the solve passes too (true), or in the relax passes only (false, as
  // Box3D does, which also leaves its rolling rows out there: ours stay): a 4-point
  // manifold's solve pass then runs its 4 normal rows instead of 12. Warm starting carries the
  // friction impulse of the last relax pass into the next sub-step, so static friction still
  // holds; without a relax pass or without warm starting friction stays in the solve passes
  // (contact_friction_while_solving, world_settings.hpp). What it costs and saves: README
  // "Contacts", "Friction while relaxing only".
  bool friction_while_solving = true;
  bool operator==(const ContactSettings&) const = default;
};

}  // namespace softstep
