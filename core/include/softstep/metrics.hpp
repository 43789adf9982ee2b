// Per-step accuracy metrics that need no reference solve (reference.hpp has the ones that do).
#pragma once

#include <span>

#include "softstep/world.hpp"

namespace softstep::metrics {

// Kinetic energy + gravitational potential energy (world gravity times gravity scale, zero
// at the origin) + the potential energy of soft springs, J. A spring of frequency f stores
// 1/2 C^T k C with k = omega^2 K^-1 (K = J M^-1 J^T of its rows now, talk 3:1): the stiffness
// the solver gives it. Rigid rows store nothing (their softness is the solver's, not the
// scene's), so this is conserved by scenes of rigid joints and undamped springs.
// Ball and distance joints only (std::invalid_argument for the angular types, whose rows the
// references do not model yet).
double mechanical_energy(const World& world, std::span<const BodyId> bodies,
                         std::span<const JointId> joints);

// sqrt(mean |p_i - q_i|^2) over the bodies' centres against reference positions q, m.
double position_drift(const World& world, std::span<const BodyId> bodies,
                      std::span<const Eigen::Vector3d> reference);

// Length of the path through the points over the rest length (1 = unstretched).
double stretch_ratio(std::span<const Eigen::Vector3d> path, double rest_length);

}  // namespace softstep::metrics
