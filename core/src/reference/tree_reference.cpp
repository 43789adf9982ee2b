// reference::solve_tree: a SoftSystem handed to the step's tree elimination, so that tests can
// hold the fast solve against the Eigen one on the same system.
#include <algorithm>
#include <stdexcept>

#include "softstep/reference.hpp"
#include "solver/tree_system.hpp"

namespace softstep::reference {
namespace {

// Whether a joint's rows against one body are sign [I, -[r]x] for some arm r.
bool ball_rows(const solver::Jac& jac, double sign) {
  const Eigen::Matrix3d linear = jac.leftCols<3>(), angular = jac.rightCols<3>();
  return linear == sign * Eigen::Matrix3d::Identity() && angular == -angular.transpose();
}

}  // namespace

ExactSolution solve_tree(const SoftSystem& s, TreeSweep sweep) {
  // Nodes: the bodies of finite mass.
  const int blocks = static_cast<int>(s.body_slots.size());
  std::vector<std::int32_t> node(static_cast<std::size_t>(blocks), -1);
  std::vector<solver::InverseMass> inverse_mass;
  const Eigen::MatrixXd dense_mass(s.mass);
  for (int b = 0; b < blocks; ++b) {
    const solver::Mat6 m = dense_mass.block<6, 6>(6 * b, 6 * b);
    if (m.isZero(0.0)) continue;  // static or kinematic
    node[static_cast<std::size_t>(b)] = static_cast<std::int32_t>(inverse_mass.size());
    // A rigid body's mass block is diag(m I, I): the tree solve takes its inverse so.
    const bool rigid_body = m.topRightCorner<3, 3>().isZero(0.0) &&
                            m.bottomLeftCorner<3, 3>().isZero(0.0) &&
                            m.topLeftCorner<3, 3>().isApprox(m(0, 0) * Eigen::Matrix3d::Identity());
    if (!rigid_body) throw std::invalid_argument("solve_tree: a mass block other than diag(m I, I)");
    inverse_mass.push_back({1.0 / m(0, 0), m.bottomRightCorner<3, 3>().inverse()});
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> jac(s.jacobian);
  const Eigen::VectorXd residual = s.jacobian * s.velocity_before + s.bias;
  std::vector<solver::TreeJoint> joints;
  int row = 0;
  for (int count : s.joint_rows) {
    solver::TreeJoint t;
    t.rows = count;
    // The joint's bodies in column order: side 0 and side 1 of its rows.
    std::vector<int> seen;
    for (int r = row; r < row + count; ++r) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(jac, r); it; ++it) {
        const int b = static_cast<int>(it.col()) / 6;
        if (std::find(seen.begin(), seen.end(), b) == seen.end()) seen.push_back(b);
      }
    }
    std::sort(seen.begin(), seen.end());
    if (seen.size() > 2) throw std::invalid_argument("solve_tree: a joint on more than two bodies");
    for (std::size_t side = 0; side < seen.size(); ++side) {
      const int b = seen[side];
      t.body[side] = node[static_cast<std::size_t>(b)];
      for (int r = 0; r < count; ++r) {
        for (int c = 0; c < 6; ++c) t.jacobian[side](r, c) = s.jacobian.coeff(row + r, 6 * b + c);
      }
    }
    // first_substep_system holds ball joints (3 rows) and distance joints (1) only; a ball
    // joint's rows are s [I, -[r]x] on each side, which the links' elimination then reads back
    // (TreeJoint::ball), checked here entry by entry.
    t.ball = count == 3 && seen.size() == 2 && ball_rows(t.jacobian[0], -1.0) &&
             ball_rows(t.jacobian[1], 1.0);
    if (t.ball) solver::set_ball_arms(t);
    for (int i = 0; i < count; ++i) {
      t.residual[i] = residual[row + i];
      for (int k = 0; k < count; ++k) t.gamma(i, k) = s.softness.coeff(row + i, row + k);
    }
    joints.push_back(t);
    row += count;
  }
  solver::TreeSystem system;
  if (!system.build(static_cast<std::uint32_t>(inverse_mass.size()), joints)) {
    throw std::invalid_argument(
        "solve_tree: the joints do not form a tree (a loop through movable bodies or through "
        "the ground)");
  }
  std::vector<solver::Vec6> dv;
  std::vector<Eigen::Vector3d> dp;
  if (sweep == TreeSweep::Separate) {
    system.solve(inverse_mass, joints, dv, dp);
  } else {
    dv.resize(inverse_mass.size());
    dp.resize(joints.size());
    system.factor_solve_up<1>(0, inverse_mass, joints, {});
    system.factor_solve_up<1>(1, inverse_mass, joints, {});
    system.factor_solve_root<1>(inverse_mass, joints, dv, dp);
    system.solve_down<1>(0, joints, dv, dp);
    system.solve_down<1>(1, joints, dv, dp);
  }
  ExactSolution x;
  x.impulse.resize(s.rows());
  row = 0;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    for (int r = 0; r < joints[j].rows; ++r) x.impulse[row + r] = dp[j][r];
    row += joints[j].rows;
  }
  x.velocity = s.velocity_before;
  for (int b = 0; b < blocks; ++b) {
    const std::int32_t n = node[static_cast<std::size_t>(b)];
    if (n >= 0) x.velocity.segment<6>(6 * b) += dv[static_cast<std::size_t>(n)];
  }
  return x;
}

}  // namespace softstep::reference
