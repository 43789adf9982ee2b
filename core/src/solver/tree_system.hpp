// The exact solve of one sub-step's soft system on an island whose joints form a tree
// (Baraff, "Linear-time dynamics using Lagrange multipliers", SIGGRAPH 1996).
//
// The system (reference.hpp, DESIGN.md "The math in one place"), written with the body
// velocities kept as unknowns:
//     [ M   J^T ] [ dv ]   [ 0  ]         dP = -lambda
//     [ J  -Gam ] [ lam] = [ -r ]         r  = J v + bias + Gamma P   (the row residual)
// Its sparsity graph has a node per body and per joint and an edge where a joint touches a
// movable body. When that graph is a tree (a chain, a rope, a ragdoll, a bridge pinned at both
// ends: static and kinematic bodies are not nodes), eliminating the nodes leaves first creates
// no fill: each node's block is reduced by its children's Schur complements and the system is
// solved in time linear in its rows. Bodies are 6x6 blocks, joints 3x3 (a joint of fewer rows
// pads its block with -1 on the diagonal and zero Jacobian rows, whose unknowns come out 0).
// A body of at most one child joint (a chain link) is eliminated together with that joint, in
// joint space: along a chain the system is block-tridiagonal in the joints' 3x3 blocks, and a
// link has no 6x6 block of its own.
//
// Double precision (a link's products on rows of three doubles, tree_system.cpp), each island
// in an order of its own (never the thread count's; its two halves may run on two threads at
// once, split below), outside the kernels' width dispatch: the same bits at every SIMD width
// and thread count.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

namespace softstep::solver {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Jac = Eigen::Matrix<double, 3, 6>;  // a joint's rows against one body (v, then w)
using Vec6x2 = Eigen::Matrix<double, 6, 2>;
using Vec3x2 = Eigen::Matrix<double, 3, 2>;
// The right sides of a solve beyond its first (column 0, from the joints' residuals): column c
// from more[c - 1], one per joint.
using MoreSides = std::array<const std::vector<Eigen::Vector3d>*, 2>;

// A rigid body's M^-1 = diag(linear I, angular): its inverse mass and its world inverse
// inertia, symmetric (a chain link reads its rows as its columns).
struct InverseMass {
  double linear = 0.0;
  Eigen::Matrix3d angular = Eigen::Matrix3d::Zero();
};

// One joint as the tree solve sees it. body[s] is the island-local index of side s's body,
// or -1 when that body does not move (static, kinematic): its velocity is already in r.
struct TreeJoint {
  std::int32_t body[2] = {-1, -1};
  int rows = 3;  // 1..3; rows beyond are padding
  // A ball joint's rows, s [I, -[r]x] on each side (s = -1 on side 0, +1 on side 1, r the
  // anchor's arm from the body's centre): the elimination and the solve of a chain link
  // between two such joints read s and a = -s r (`arm`, padded to four doubles: one load) and
  // form their products from them (tree_system.cpp, BallLinkProducts). A ball joint's `arm`
  // must be set with its blocks (set_ball_arms from the blocks).
  bool ball = false;
  double arm[2][4] = {};
  // Per side. A ball joint's are read only where TreeSystem::reads_blocks says: elsewhere the
  // caller may leave them as they were.
  Jac jacobian[2] = {Jac::Zero(), Jac::Zero()};
  Eigen::Matrix3d gamma = Eigen::Matrix3d::Zero();     // symmetric (a chain link relies on it)
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();  // r = J v + bias + Gamma P
};

// A ball joint's `arm` from its blocks (a = -s r, the blocks' angular entries).
void set_ball_arms(TreeJoint& joint);

// The elimination order of an island, built once per topology: every node after its
// children. A node is a body or a joint; `side` says which end of the joint the edge to the
// parent is (for a joint whose parent is a body, and a body whose parent is a joint).
struct TreeNode {
  bool joint = false;
  std::uint32_t index = 0;    // island-local body or joint index
  std::int32_t parent = -1;   // position in the order; -1 for the root (last)
  std::uint8_t side = 0;
};

class TreeSystem {
 public:
  // Orders the island's bodies and joints (each joint's body[] set). Returns false when the
  // graph has a loop or is not connected: it is not one tree, and this island is not solved
  // here. An island of kSplitJoints joints or more is rooted at its centre and split in two
  // parts (tree_system.cpp); the order depends on the island only, never on the threads.
  bool build(std::uint32_t bodies, const std::vector<TreeJoint>& joints);
  static constexpr std::size_t kSplitJoints = 8;

  // The elimination in three parts: parts 0 and 1, each a half of the tree below its root's
  // children, touch disjoint nodes (two threads may run them at once), and the root part (the
  // root and its children) joins them. The same operations in the same order whoever runs
  // them: a factor is factor_part(0), factor_part(1), factor_root(); a solve is solve_up(0),
  // solve_up(1), solve_root(), solve_down(0), solve_down(1). The two parts' calls may run at
  // once; the root part's call must come after both parts' calls before it and before both
  // after it. An island that is not split has all its nodes in part 0 and the root part.
  bool split() const { return segment_[1].end > segment_[1].begin; }
  // The part a body or joint belongs to (0 or 1): the root part's root is part 0's, its
  // children the part they top. The caller's per-body and per-joint work follows it.
  int body_part(std::uint32_t body) const { return body_part_[body]; }
  int joint_part(std::uint32_t joint) const { return joint_part_[joint]; }
  // Whether a factor or solve reads joint j's 3x6 blocks (TreeJoint::jacobian): always for a
  // joint that is not a ball joint; for a ball joint, where one of its bodies is not a chain
  // link between ball joints (a body of many children, a link beside another kind of joint).
  // The exact passes write a ball joint's blocks only there: the whip's 1,000 links read
  // only their arms, and the rows pass wrote 288 bytes a joint that nobody read.
  bool reads_blocks(std::uint32_t joint) const { return reads_blocks_[joint] != 0; }

  // Factors H for these inverse masses (W = M^-1 per body: the solver keeps inverse masses,
  // and a chain link is eliminated with W, tree_system.cpp) and Jacobians and Gammas, leaves
  // first. The solves read inverse_mass's elements, as they read the joints: keep both as they
  // were given here until the last solve with this factor (factor_root keeps the pointer).
  void factor_part(int part, const std::vector<InverseMass>& inverse_mass,
                   const std::vector<TreeJoint>& joints);
  void factor_root(const std::vector<InverseMass>& inverse_mass,
                   const std::vector<TreeJoint>& joints);
  // The solve with the last factor, Columns (1 to 3) right sides: column 0 from the joints'
  // residuals r, the others from `more`. Results: the velocity change of
  // every body (6 each: v then w) and the impulse change of every joint (3 each; padding rows
  // 0), into dv and dp sized for the island's bodies and joints. The pass's time is its chain
  // of dependent small products from the leaves to the root and back, which two independent
  // columns share: the relax pass solves its velocities and the position projection together
  // (and the next sub-step's velocity change, tree_solver.hpp).
  template <int Columns>
  void solve_up(int part, const std::vector<TreeJoint>& joints, const MoreSides& more);
  template <int Columns>
  void solve_root(const std::vector<TreeJoint>& joints,
                  std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                  std::vector<Eigen::Matrix<double, 3, Columns>>& dp);
  template <int Columns>
  void solve_down(int part, const std::vector<TreeJoint>& joints,
                  std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                  std::vector<Eigen::Matrix<double, 3, Columns>>& dp);

  // factor_part and solve_up in one pass over the part's nodes, and factor_root and solve_root:
  // each node's forward step right after its elimination, a chain link's from its E^-1 and y
  // still in registers (the same operations in the same order: the same bits as the calls
  // apart). The solver's passes factor and solve at once.
  template <int Columns>
  void factor_solve_up(int part, const std::vector<InverseMass>& inverse_mass,
                       const std::vector<TreeJoint>& joints, const MoreSides& more);
  template <int Columns>
  void factor_solve_root(const std::vector<InverseMass>& inverse_mass,
                         const std::vector<TreeJoint>& joints,
                         std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                         std::vector<Eigen::Matrix<double, 3, Columns>>& dp);

  // All parts on one thread.
  void factor(const std::vector<InverseMass>& inverse_mass, const std::vector<TreeJoint>& joints);
  void solve(const std::vector<TreeJoint>& joints, std::vector<Vec6>& dv,
             std::vector<Eigen::Vector3d>& dp);
  void solve(const std::vector<TreeJoint>& joints, const std::vector<Eigen::Vector3d>& second,
             std::vector<Vec6x2>& dv, std::vector<Vec3x2>& dp);
  // factor, then solve.
  void solve(const std::vector<InverseMass>& inverse_mass, const std::vector<TreeJoint>& joints,
             std::vector<Vec6>& dv, std::vector<Eigen::Vector3d>& dp) {
    factor(inverse_mass, joints);
    solve(joints, dv, dp);
  }

  std::size_t nodes() const { return order_.size(); }

 private:
  // A stretch of the order: [begin, end).
  struct Span {
    std::size_t begin = 0, end = 0;
  };
  Span root_part() const { return {tops_[0].begin, order_.size()}; }  // tops and root
  Span root_node() const { return {order_.size() - 1, order_.size()}; }
  void init_blocks(Span span, const std::vector<InverseMass>& inverse_mass,
                   const std::vector<TreeJoint>& joints);
  void init_part_blocks(int part, const std::vector<InverseMass>& inverse_mass,
                        const std::vector<TreeJoint>& joints);
  // Columns > 0: with each node's forward step (factor_solve_up).
  template <int Columns>
  void eliminate(Span span, const InverseMass* inverse_mass, const std::vector<TreeJoint>& joints);
  void eliminate_node(std::size_t k, const std::vector<TreeJoint>& joints);  // not a chain link
  template <int Columns>
  void init_rhs(Span span, const std::vector<TreeJoint>& joints, const MoreSides& more);
  template <int Columns>
  void init_part_rhs(int part, const std::vector<TreeJoint>& joints, const MoreSides& more);
  template <int Columns>
  void forward(Span span, const std::vector<TreeJoint>& joints);
  template <int Columns>
  void forward_node(std::size_t k, const std::vector<TreeJoint>& joints);
  template <int Columns>
  void backward(Span span, const std::vector<TreeJoint>& joints,
                std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                std::vector<Eigen::Matrix<double, 3, Columns>>& dp);
  template <int Columns>
  std::vector<Eigen::Matrix<double, 6, Columns>>& body_rhs();
  template <int Columns>
  std::vector<Eigen::Matrix<double, 3, Columns>>& joint_rhs();

  // A body of at most one child joint (a chain link), and a joint whose parent is one.
  bool is_link(const TreeNode& node) const {
    return !node.joint && body_child_[node.index] != kManyChildren;
  }
  bool under_link(const TreeNode& node) const {
    return node.parent >= 0 && is_link(order_[static_cast<std::size_t>(node.parent)]);
  }
  template <int Columns>
  void eliminate_link(std::size_t k, const InverseMass* inverse_mass,
                      const std::vector<TreeJoint>& joints);
  // The elimination proper, with the link's products formed by `products` (tree_system.cpp:
  // from the general blocks, or from ball joints' arms), and with Columns > 0 its forward step.
  template <int Columns, class Products>
  void eliminate_link_with(const TreeNode& link, Products& products);
  // A chain link whose parent and child joints (those it has) are ball joints
  // (TreeJoint::ball): its factor and solve steps read their signs and arms.
  bool ball_link(const TreeNode& link, const std::vector<TreeJoint>& joints) const {
    const std::int32_t child = body_child_[link.index];
    return (link.parent < 0 || joints[order_[static_cast<std::size_t>(link.parent)].index].ball) &&
           (child == kNoChild || joints[static_cast<std::size_t>(child)].ball);
  }

  // [part 0's nodes][part 1's][the root's children of part 0][of part 1][the root]
  std::vector<TreeNode> order_;
  Span segment_[2], tops_[2];
  std::vector<std::uint8_t> body_part_, joint_part_, reads_blocks_;
  // Scratch, sized once in build: per body of many children the reduced block, then its
  // inverse, and the transfer towards its parent joint (sized for every body; a chain link
  // uses inverse_mass_, link_e_inverse_ and link_y_ below instead); per joint the reduced block
  // and, unless it is a link's child, its inverse; the right sides. Fixed-size blocks and
  // hand-ordered 3x3 arithmetic (tree_system.cpp says why).
  std::vector<Mat6> body_block_;                            // B, then B^-1 once eliminated
  std::vector<Eigen::Matrix<double, 6, 3>> body_transfer_;  // B^-1 J^T towards the parent
  template <int Columns>
  using BodySides = std::vector<Eigen::Matrix<double, 6, Columns>>;
  template <int Columns>
  using JointSides = std::vector<Eigen::Matrix<double, 3, Columns>>;
  std::tuple<BodySides<1>, BodySides<2>, BodySides<3>> body_rhs_;  // per number of columns
  // Three rows or columns of a 3x3 block, each padded to four doubles (the last 0): one vector
  // load or store each in a chain link's elimination and solve, where col-major a row took
  // three scalar loads or stores.
  struct alignas(32) Padded3 {
    double v[3][4] = {};
  };
  using PaddedRows =
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>, 0, Eigen::OuterStride<4>>;
  // D, the reduced joint block, by rows: a chain link reduces its parent joint's and reads its
  // child joint's a row at a time (scalar by scalar col-major, 2 % of the whip's exact step,
  // Zen 5).
  std::vector<Padded3> joint_block_;
  std::vector<Eigen::Matrix3d> joint_inverse_;  // D^-1
  std::tuple<JointSides<1>, JointSides<2>, JointSides<3>> joint_rhs_;
  // Per body its one child joint (a chain link), kNoChild (a leaf) or kManyChildren; and the
  // side of that joint at the body. A body of at most one child is eliminated with its child
  // joint in joint space (tree_system.cpp, eliminate_link).
  static constexpr std::int32_t kNoChild = -1;
  static constexpr std::int32_t kManyChildren = -2;
  std::vector<std::int32_t> body_child_;
  std::vector<std::uint8_t> body_child_side_;
  // The last factor's W per body, the caller's (a chain link's solve reads it; not copied: on
  // 100 chains of 1,000 links a copy per factor was 80 bytes a link more for each sub-step's
  // island to hold in cache); per chain link (a body of at most one child joint;
  // tree_system.cpp, eliminate_link): E^-1 and y = E^-1 K_cp.
  const InverseMass* inverse_mass_ = nullptr;
  std::vector<Padded3> link_e_inverse_;  // by columns
  std::vector<Padded3> link_y_;          // by columns
};

}  // namespace softstep::solver
