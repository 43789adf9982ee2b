// The exact solution of one sub-step's soft system (reference.hpp).
#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "reference/joint_rows.hpp"
#include "softstep/reference.hpp"

namespace softstep::reference {

namespace {
using Triplets = std::vector<Eigen::Triplet<double>>;

void add_block(Triplets& t, int row, int col, const Eigen::MatrixXd& block) {
  for (int i = 0; i < block.rows(); ++i) {
    for (int j = 0; j < block.cols(); ++j) {
      if (block(i, j) != 0.0) t.emplace_back(row + i, col + j, block(i, j));
    }
  }
}
}  // namespace

SoftSystem first_substep_system(const World& world) {
  const SolveCapture& c = world.solve_capture();
  if (c.h <= 0.0) throw std::logic_error("first_substep_system: no step captured");
  const WorldSettings& settings = world.settings();
  const auto frame_of = [&c](BodyId id) {
    return BodyFrame{c.position[id.index], c.orientation[id.index], c.inverse_mass[id.index],
                     c.inverse_inertia[id.index]};
  };
  SoftSystem s;
  s.h = c.h;
  std::unordered_map<std::uint32_t, int> block_of;  // body slot -> 6-column block
  const auto block = [&](std::uint32_t slot) {
    const auto [it, added] = block_of.try_emplace(slot, static_cast<int>(s.body_slots.size()));
    if (added) s.body_slots.push_back(slot);
    return it->second;
  };
  Triplets jacobian, softness;
  std::vector<double> bias, bound, impulse;
  const Spring rigid = Spring::soft(c.rigid_hertz, settings.rigid_damping_ratio);
  for (std::size_t k = 0; k < c.joints.size(); ++k) {
    const JointRows rows = joint_rows(world, c.joints[k], frame_of);
    if (rows.has_limits) {
      throw std::invalid_argument(
          "first_substep_system: distance-joint limit rows (unilateral) are not modelled");
    }
    if (rows.count == 0) continue;
    const int row = static_cast<int>(bias.size());
    s.joint_rows.push_back(rows.count);
    add_block(jacobian, row, 6 * block(rows.body_a), rows.jacobian.block(0, 0, rows.count, 6));
    add_block(jacobian, row, 6 * block(rows.body_b), rows.jacobian.block(0, 6, rows.count, 6));
    // gamma and bias_rate with m_eff = 1: Gamma = (gamma / h) K (talk 2:3:2).
    const SoftCoefficients soft =
        (rows.spring.is_rigid() ? rigid : rows.spring).coefficients(1.0, c.h);
    add_block(softness, row, row,
              (soft.gamma / c.h) * rows.k.topLeftCorner(rows.count, rows.count));
    for (int r = 0; r < rows.count; ++r) {
      bias.push_back(soft.bias_rate * rows.error[r]);
      bound.push_back(rows.spring.is_rigid() ? settings.max_correction_speed
                                             : std::numeric_limits<double>::infinity());
      impulse.push_back(c.impulse[k][r]);
    }
  }
  const int n = static_cast<int>(bias.size());
  const int columns = 6 * static_cast<int>(s.body_slots.size());
  s.jacobian.resize(n, columns);
  s.jacobian.setFromTriplets(jacobian.begin(), jacobian.end());
  s.softness.resize(n, n);
  s.softness.setFromTriplets(softness.begin(), softness.end());
  s.bias = Eigen::Map<const Eigen::VectorXd>(bias.data(), n);
  s.bias_bound = Eigen::Map<const Eigen::VectorXd>(bound.data(), n);
  s.impulse_after_solve = Eigen::Map<const Eigen::VectorXd>(impulse.data(), n);
  Triplets inverse_mass, mass;
  s.velocity_before.resize(columns);
  s.velocity_after_solve.resize(columns);
  for (std::size_t b = 0; b < s.body_slots.size(); ++b) {
    const std::uint32_t slot = s.body_slots[b];
    const int at = 6 * static_cast<int>(b);
    s.velocity_before.segment<6>(at) = c.velocity_before_solve[slot];
    s.velocity_after_solve.segment<6>(at) = c.velocity_after_solve[slot];
    if (c.inverse_mass[slot] == 0.0) continue;  // static or kinematic: infinite mass
    const Eigen::Matrix3d linear = c.inverse_mass[slot] * Eigen::Matrix3d::Identity();
    add_block(inverse_mass, at, at, linear);
    add_block(inverse_mass, at + 3, at + 3, c.inverse_inertia[slot]);
    add_block(mass, at, at, Eigen::Matrix3d(linear.inverse()));
    add_block(mass, at + 3, at + 3, Eigen::Matrix3d(c.inverse_inertia[slot].inverse()));
  }
  s.inverse_mass.resize(columns, columns);
  s.inverse_mass.setFromTriplets(inverse_mass.begin(), inverse_mass.end());
  s.mass.resize(columns, columns);
  s.mass.setFromTriplets(mass.begin(), mass.end());
  return s;
}

ExactSolution solve_exact(const SoftSystem& s) {
  const Eigen::SparseMatrix<double> a =
      Eigen::SparseMatrix<double>(s.jacobian * s.inverse_mass * s.jacobian.transpose()) +
      s.softness;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  if (ldlt.info() != Eigen::Success) {
    throw std::runtime_error("solve_exact: the soft system could not be factorized");
  }
  ExactSolution x;
  x.impulse = ldlt.solve(-(s.jacobian * s.velocity_before + s.bias));
  x.velocity = s.velocity_before + s.inverse_mass * (s.jacobian.transpose() * x.impulse);
  const Eigen::VectorXd asked = s.bias + s.softness * x.impulse;  // the speed each row closes at
  for (int r = 0; r < s.rows(); ++r) x.bounded_rows += std::abs(asked[r]) > s.bias_bound[r];
  return x;
}

VectorX row_residual(const SoftSystem& s, const VectorX& velocity, const VectorX& impulse) {
  return s.jacobian * velocity + s.bias + s.softness * impulse;
}

double energy_norm(const SoftSystem& s, const VectorX& dv) {
  return std::sqrt(std::max(0.0, dv.dot(s.mass * dv)));
}

double reference_distance(const SoftSystem& s, const ExactSolution& exact) {
  const double scale = energy_norm(s, exact.velocity - s.velocity_before);
  const double off = energy_norm(s, s.velocity_after_solve - exact.velocity);
  return scale > 0.0 ? off / scale : off;
}

}  // namespace softstep::reference
