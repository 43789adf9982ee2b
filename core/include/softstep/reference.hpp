// Exact references for the accuracy measurements (DESIGN.md, "Accuracy has a price").
//
// One sub-step's soft-constraint system (talk 2:3, DESIGN.md "The math in one place"):
//   v = v0 + M^-1 J^T P,      J v + bias + Gamma P = 0
// with, per row, bias = bias_rate C and Gamma the softness gamma/h times the joint's block of
// K = J M^-1 J^T (the solver's gamma' = feedback K). Eliminating v:
//   (J M^-1 J^T + Gamma) P = -(J v0 + bias)
// which is symmetric positive definite and solved here with a sparse Cholesky (Eigen's
// SimplicialLDLT). Its solution is the fixed point of the solver's Gauss-Seidel passes: what
// infinitely many solve iterations converge to.
//
// Built from a World's SolveCapture (World::set_solve_capture), so it holds exactly the state,
// masses (with the geometric-stiffness inertia when on) and sub-step the solver used.
// Differences from the solver, by design:
//  - a rigid row's bias is bounded by max_correction_speed in the solver; here it is not
//    (ExactSolution::bounded_rows counts the rows where the bound would have acted);
//  - distance joints with limit rows (unilateral) are rejected: only equalities are modelled;
//  - the reference is double precision, the solver float (about 1e-6 relative rounding).
// Its vectors are VectorX (eigen_types.hpp): created in the library, freed in the program,
// whatever flags each was built with.
#pragma once

#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

#include "softstep/eigen_types.hpp"
#include "softstep/world.hpp"

namespace softstep::reference {

struct SoftSystem {
  double h = 0.0;                            // the sub-step, s
  std::vector<std::uint32_t> body_slots;     // the body of each 6-column block (v then w)
  Eigen::SparseMatrix<double> jacobian;      // rows x 6 bodies
  Eigen::SparseMatrix<double> inverse_mass;  // 6 bodies square, block diagonal
  Eigen::SparseMatrix<double> mass;          // its inverse (0 for infinite-mass bodies)
  Eigen::SparseMatrix<double> softness;      // Gamma, rows square, block diagonal, 1/kg
  VectorX bias;                              // bias_rate C per row, m/s
  VectorX bias_bound;                        // m/s, bound on |bias + Gamma P|: +inf for springs
  VectorX velocity_before;                   // v0: after gravity and damping, before the solve
  VectorX velocity_after_solve;              // what the solver reached
  VectorX impulse_after_solve;               // the impulses it accumulated, N s
  std::vector<int> joint_rows;               // rows of each joint, in row order
  int rows() const { return static_cast<int>(bias.size()); }
};

// The first sub-step of the world's last step. Throws std::logic_error when the world has no
// capture, std::invalid_argument for a distance joint with limit rows or a joint of a type
// other than ball and distance (their rows are not modelled here yet).
SoftSystem first_substep_system(const World& world);

struct ExactSolution {
  VectorX velocity;      // 6 per body, as SoftSystem::body_slots
  VectorX impulse;       // per row, N s
  int bounded_rows = 0;  // rows whose bias bound the solver would have applied
};
ExactSolution solve_exact(const SoftSystem& system);

// The same system solved by the step's linear-time tree elimination (WorldSettings::solver =
// DirectForTrees, core/src/solver/tree_system.hpp): equal to solve_exact up to rounding when
// the joints form a tree. Throws std::invalid_argument when they do not (a loop through
// movable bodies, or more than one joint to static or kinematic bodies in one island).
// Separate: the factor, then the solve; OneSweep: each node's forward step right after its
// elimination, as the step's exact passes run it (the same bits, promised and tested).
enum class TreeSweep { Separate, OneSweep };
ExactSolution solve_tree(const SoftSystem& system, TreeSweep sweep = TreeSweep::Separate);

// J v + bias + Gamma P per row, m/s: zero for the exact solution.
VectorX row_residual(const SoftSystem& system, const VectorX& velocity, const VectorX& impulse);
// sqrt(dv^T M dv): the kinetic-energy norm of a velocity difference, sqrt(J) = sqrt(kg) m/s.
double energy_norm(const SoftSystem& system, const VectorX& dv);
// How far the solver's velocities are from the exact ones, relative to how much the exact
// solve changes the velocities: |v - v*|_M / |v* - v0|_M (0 when v0 already solves it).
double reference_distance(const SoftSystem& system, const ExactSolution& exact);

}  // namespace softstep::reference
