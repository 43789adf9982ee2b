#include "solver/tree_system.hpp"

#include <Eigen/LU>

namespace softstep::solver {

bool TreeSystem::build(std::uint32_t bodies, const std::vector<TreeJoint>& joints) {
  order_.clear();
  if (bodies == 0) return false;
  // Node ids: bodies 0 .. bodies-1, then joint j is bodies + j.
  const std::uint32_t nodes = bodies + static_cast<std::uint32_t>(joints.size());
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> around(bodies);
  std::size_t edges = 0;
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    for (std::uint8_t s = 0; s < 2; ++s) {
      const std::int32_t b = joints[j].body[s];
      if (b < 0) continue;
      around[static_cast<std::size_t>(b)].push_back({bodies + j, s});
      ++edges;
    }
  }
  if (edges + 1 != nodes) return false;  // a connected graph is a tree iff edges = nodes - 1
  // A joint on one movable body (its other end static or kinematic) is a leaf whose block,
  // -Gamma, is 0 for a rigid row: it cannot be eliminated before its body. So such a joint
  // must be the root, and an island can have one: two (a bridge pinned at both ends) close a
  // loop through the ground, which this elimination cannot order (a 9x9 body + joint block
  // would; not done), and the island stays iterative.
  std::int32_t grounded = -1;
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    if (joints[j].body[0] >= 0 && joints[j].body[1] >= 0) continue;
    if (grounded >= 0) return false;
    grounded = static_cast<std::int32_t>(j);
  }
  // Breadth first from the root: a node's parent comes before it, so the reverse is an
  // order that eliminates every node after its children. Without a grounded joint the root is
  // body 0, and every joint has a child body.
  std::vector<TreeNode> bfs;
  bfs.reserve(nodes);
  std::vector<bool> seen(nodes, false);
  if (grounded >= 0) {
    bfs.push_back({true, static_cast<std::uint32_t>(grounded), -1, 0});
    seen[bodies + static_cast<std::uint32_t>(grounded)] = true;
  } else {
    bfs.push_back({false, 0, -1, 0});
    seen[0] = true;
  }
  for (std::size_t k = 0; k < bfs.size(); ++k) {
    const TreeNode n = bfs[k];
    const auto here = static_cast<std::int32_t>(k);
    if (n.joint) {
      const TreeJoint& j = joints[n.index];
      for (std::uint8_t s = 0; s < 2; ++s) {
        const std::int32_t b = j.body[s];
        if (b < 0 || seen[static_cast<std::size_t>(b)]) continue;
        seen[static_cast<std::size_t>(b)] = true;
        bfs.push_back({false, static_cast<std::uint32_t>(b), here, s});
      }
    } else {
      for (const auto& [node, side] : around[n.index]) {
        if (seen[node]) continue;
        seen[node] = true;
        bfs.push_back({true, node - bodies, here, side});
      }
    }
  }
  if (bfs.size() != nodes) return false;  // not connected
  order_.resize(nodes);
  const auto last = static_cast<std::int32_t>(nodes) - 1;
  for (std::size_t k = 0; k < nodes; ++k) {
    TreeNode n = bfs[k];
    if (n.parent >= 0) n.parent = last - n.parent;
    order_[static_cast<std::size_t>(last) - k] = n;
  }
  body_block_.resize(bodies);
  body_transfer_.resize(bodies);
  body_rhs_.resize(bodies);
  body_rhs_pair_.resize(bodies);
  joint_block_.resize(joints.size());
  joint_inverse_.resize(joints.size());
  joint_rhs_.resize(joints.size());
  joint_rhs_pair_.resize(joints.size());
  body_child_.assign(bodies, kNoChild);
  body_child_side_.assign(bodies, 0);
  for (const TreeNode& n : order_) {
    if (!n.joint || n.parent < 0) continue;
    const std::uint32_t body = order_[static_cast<std::size_t>(n.parent)].index;
    body_child_[body] =
        body_child_[body] == kNoChild ? static_cast<std::int32_t>(n.index) : kManyChildren;
    body_child_side_[body] = n.side;
  }
  return true;
}

namespace {

using Mat63 = Eigen::Matrix<double, 6, 3>;

// B^-1 of a reduced body block, B = [A C; C^T D] in 3x3 blocks (linear, then angular): A is
// m I plus what child joints add, D the inertia plus theirs, both positive definite, so is
// the Schur complement S = D - C^T A^-1 C. Two 3x3 inverses (cofactors) and four 3x3 products,
// all fixed-size and inlined: Eigen's LLT<Mat6> ran its factor and its triangular solves
// through the dynamic-size kernels, half of the exact pass's time (perf, the 1,000-link whip).
// Same pivot order as a Cholesky of B (linear rows first).
void invert_body_block(Mat6& b) {
  const Eigen::Matrix3d a_inverse = b.topLeftCorner<3, 3>().inverse();
  const Eigen::Matrix3d g = a_inverse * b.topRightCorner<3, 3>();  // A^-1 C
  const Eigen::Matrix3d s = b.bottomRightCorner<3, 3>() - b.topRightCorner<3, 3>().transpose() * g;
  const Eigen::Matrix3d s_inverse = s.inverse();
  const Eigen::Matrix3d g_s = g * s_inverse;  // A^-1 C S^-1
  b.topLeftCorner<3, 3>() = a_inverse + g_s * g.transpose();
  b.topRightCorner<3, 3>() = -g_s;
  b.bottomLeftCorner<3, 3>() = -g_s.transpose();
  b.bottomRightCorner<3, 3>() = s_inverse;
}

}  // namespace

void TreeSystem::factor(const std::vector<Mat6>& inverse_mass,
                        const std::vector<TreeJoint>& joints) {
  // The blocks of H; each becomes its reduced block's inverse when its node is eliminated. A
  // body of many children sums M and their terms; the others start from W = M^-1.
  for (std::size_t b = 0; b < body_block_.size(); ++b) {
    body_block_[b] = inverse_mass[b];
    if (body_child_[b] == kManyChildren) invert_body_block(body_block_[b]);
  }
  for (std::size_t j = 0; j < joints.size(); ++j) {
    Eigen::Matrix3d d = -joints[j].gamma;
    for (int r = joints[j].rows; r < 3; ++r) {
      d.row(r).setZero();
      d.col(r).setZero();
      d(r, r) = -1.0;
    }
    joint_block_[j] = d;
  }
  const std::size_t n = order_.size();
  // Leaves first: fold each node into its parent (a Schur complement), no fill on a tree.
  // The factor is a chain of dependent small inverses from the leaves to the root, so its time
  // is their latency: a body of one child joint (every link of a chain) is eliminated in joint
  // space, where the chain's dependent work per link is one 3x3 inverse instead of three.
  for (std::size_t k = 0; k < n; ++k) {
    const TreeNode& node = order_[k];
    if (node.joint) {
      // Reduced joint blocks are negative definite (or -1 padding): a 3x3 inverse.
      joint_inverse_[node.index] = joint_block_[node.index].inverse();
      if (node.parent < 0) continue;
      const std::uint32_t body = order_[static_cast<std::size_t>(node.parent)].index;
      if (body_child_[body] != kManyChildren) continue;         // the body takes D itself
      const Jac& jac = joints[node.index].jacobian[node.side];  // E = J^T, 6x3
      const Jac scaled = joint_inverse_[node.index] * jac;
      body_block_[body].noalias() -= jac.transpose() * scaled;
      continue;
    }
    Mat6& inverse = body_block_[node.index];
    const std::int32_t child = body_child_[node.index];
    const Jac* parent_jac = nullptr;
    std::uint32_t parent_joint = 0;
    if (node.parent >= 0) {
      parent_joint = order_[static_cast<std::size_t>(node.parent)].index;
      parent_jac = &joints[parent_joint].jacobian[node.side];  // J_p, 3x6
    }
    if (child == kManyChildren) {
      // B = M + sum of J_c^T (-D_c^-1) J_c over the children, positive definite.
      invert_body_block(inverse);
      if (parent_jac == nullptr) continue;
      Mat63& transfer = body_transfer_[node.index];
      transfer.noalias() = inverse * parent_jac->transpose();
      joint_block_[parent_joint].noalias() -= *parent_jac * transfer;
      continue;
    }
    // At most one child c: B = M + J_c^T S J_c with S = -D_c^-1, so by Woodbury
    //   B^-1 = W - U_c E^-1 U_c^T,  W = M^-1, U_c = W J_c^T, E = J_c U_c - D_c,
    // and the parent's block loses J_p B^-1 J_p^T = K_pp - K_cp^T E^-1 K_cp with
    // K_xy = J_x W J_y^T. Only E^-1 waits on the child; W and the K's do not.
    Eigen::Matrix<double, 6, 3> to_parent;  // U_p = W J_p^T
    if (parent_jac != nullptr) to_parent.noalias() = inverse * parent_jac->transpose();
    if (child == kNoChild) {
      if (parent_jac == nullptr) continue;
      body_transfer_[node.index] = to_parent;
      joint_block_[parent_joint].noalias() -= *parent_jac * to_parent;
      continue;
    }
    const auto c = static_cast<std::uint32_t>(child);
    const Jac& child_jac = joints[c].jacobian[body_child_side_[node.index]];
    Mat63 to_child;  // U_c
    to_child.noalias() = inverse * child_jac.transpose();
    Eigen::Matrix3d e = child_jac * to_child;
    e -= joint_block_[c];
    const Eigen::Matrix3d e_inverse = e.inverse();
    if (parent_jac != nullptr) {
      Eigen::Matrix3d k_cp;
      k_cp.noalias() = child_jac * to_parent;
      Eigen::Matrix3d y;
      y.noalias() = e_inverse * k_cp;
      Eigen::Matrix3d k_pp;
      k_pp.noalias() = *parent_jac * to_parent;
      k_pp.noalias() -= k_cp.transpose() * y;
      joint_block_[parent_joint] -= k_pp;
      Mat63& transfer = body_transfer_[node.index];
      transfer = to_parent;
      transfer.noalias() -= to_child * y;
    }
    const Mat63 scaled = to_child * e_inverse;
    inverse.noalias() -= scaled * to_child.transpose();
  }
}

template <int Columns>
void TreeSystem::solve_columns(const std::vector<TreeJoint>& joints,
                               const std::vector<Eigen::Vector3d>* second,
                               std::vector<Eigen::Matrix<double, 6, Columns>>& body_rhs,
                               std::vector<Eigen::Matrix<double, 3, Columns>>& joint_rhs,
                               std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                               std::vector<Eigen::Matrix<double, 3, Columns>>& dp) const {
  using JointColumns = Eigen::Matrix<double, 3, Columns>;
  using BodyColumns = Eigen::Matrix<double, 6, Columns>;
  for (BodyColumns& b : body_rhs) b.setZero();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joint_rhs[j].col(0) = -joints[j].residual;
    if constexpr (Columns == 2) joint_rhs[j].col(1) = -(*second)[j];
    for (int r = joints[j].rows; r < 3; ++r) joint_rhs[j].row(r).setZero();
  }
  const std::size_t n = order_.size();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const TreeNode& node = order_[k];
    const TreeNode& parent = order_[static_cast<std::size_t>(node.parent)];
    if (node.joint) {
      const Jac& jac = joints[node.index].jacobian[node.side];
      const JointColumns scaled = joint_inverse_[node.index] * joint_rhs[node.index];
      body_rhs[parent.index].noalias() -= jac.transpose() * scaled;
    } else {
      joint_rhs[parent.index].noalias() -=
          body_transfer_[node.index].transpose() * body_rhs[node.index];
    }
  }
  dv.resize(body_block_.size());
  dp.resize(joint_inverse_.size());
  // The root, then every node from its parent's solution (root first).
  const TreeNode& root = order_[n - 1];
  if (root.joint) {
    dp[root.index].noalias() = joint_inverse_[root.index] * joint_rhs[root.index];
  } else {
    dv[root.index].noalias() = body_block_[root.index] * body_rhs[root.index];
  }
  for (std::size_t k = n - 1; k-- > 0;) {
    const TreeNode& node = order_[k];
    const TreeNode& parent = order_[static_cast<std::size_t>(node.parent)];
    if (node.joint) {
      const Jac& jac = joints[node.index].jacobian[node.side];
      const JointColumns rhs = joint_rhs[node.index] - jac * dv[parent.index];
      dp[node.index].noalias() = joint_inverse_[node.index] * rhs;
    } else {
      const Jac& jac = joints[parent.index].jacobian[node.side];
      const BodyColumns rhs = body_rhs[node.index] - jac.transpose() * dp[parent.index];
      dv[node.index].noalias() = body_block_[node.index] * rhs;
    }
  }
  // The unknown of a joint is lambda = -dP.
  for (JointColumns& p : dp) p = -p;
}

void TreeSystem::solve(const std::vector<TreeJoint>& joints, std::vector<Vec6>& dv,
                       std::vector<Eigen::Vector3d>& dp) {
  solve_columns<1>(joints, nullptr, body_rhs_, joint_rhs_, dv, dp);
}

void TreeSystem::solve(const std::vector<TreeJoint>& joints,
                       const std::vector<Eigen::Vector3d>& second, std::vector<Vec6x2>& dv,
                       std::vector<Vec3x2>& dp) {
  solve_columns<2>(joints, &second, body_rhs_pair_, joint_rhs_pair_, dv, dp);
}

}  // namespace softstep::solver
