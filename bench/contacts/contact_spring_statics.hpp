// Where soft contacts come to rest under gravity: the static solve of the contact springs.
//
// A soft contact's normal row is a spring while solving (the talk's soft constraint, "Soft
// Step"): in steady state with warm starting, the accumulated impulse lambda of a sub-step h
// and the row's position error C satisfy (the velocity terms vanish at rest)
//   0 = -m_eff mass_scale (bias_rate C) - impulse_scale lambda
// and with the talk's coefficients (zeta, omega = 2 pi hertz)
//   impulse_scale / (mass_scale bias_rate) = 1 / (h omega^2),
// so C = -(lambda / h) / (m_eff omega^2): a spring of stiffness k = m_eff omega^2 holding the
// force lambda / h, whatever the damping ratio. A stack at rest is therefore a linear network
// of such springs (one per contact point, along its normal, m_eff the row's own effective mass
// from both bodies' inverse mass and inertia at its arms) loaded by the bodies' weights; this
// solves that network for every body's displacement from the pose the manifolds were found
// at (small displacements: the arms and normals stay those of the start).
//
// Friction is not in the model: its rows are rigid and only hold sideways motion (under pure
// vertical loads on a symmetric stack they carry next to nothing); body directions the springs
// do not hold (sliding, turning about the normal) get a vanishing stiffness so the solve is
// regular, and no load, so they stay at 0.
#pragma once

#include <span>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::bench {

struct BodyDisplacement {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m, of the centre of mass
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad, small rotation vector
};

// The displacement of each of `bodies` (the dynamic ones; others are held fixed) at which the
// contact springs of `contacts` (found at the world's current poses) carry the bodies'
// weights under the world's gravity, with the contact hertz of the world's settings.
std::vector<BodyDisplacement> contact_spring_rest(const World& world,
                                                  std::span<const BodyId> bodies,
                                                  std::span<const ContactManifold> contacts);

// The lowest contact hertz at which a wall one body thick stands on its contact springs
// against tipping over sideways (about a horizontal axis in its plane; `across` is the
// wall's horizontal normal). A tall wall on springs is an inverted pendulum: tilting the rows
// above an interface by phi releases gravity energy W phi^2 / 2 and stores spring energy
// kappa (delta phi)^2 / 2, kappa = sum over the interface's points of k d^2 (d the point's
// distance from the wall's mid-plane, k = m_eff omega^2). With the rows as rigid links
// (`bodies` grouped by the height of their centres), the wall stands while
//   omega^2 K - W  is positive definite,
// K the chain's tridiagonal spring matrix per omega^2 and W diagonal, W_r = g (the mass above
// row r times the row's height + each of row r's masses times its centre's height above the
// row's contact interface). This returns the hertz where it stops being so. A tower of 10
// one-metre boxes needs 16 Hz, 20 need 45 Hz; the pyramid of base 40 needs 47 Hz, base 100
// 180 Hz.
double wall_tipping_hertz(const World& world, std::span<const BodyId> bodies,
                          std::span<const ContactManifold> contacts,
                          const Eigen::Vector3d& across);

}  // namespace softstep::bench
