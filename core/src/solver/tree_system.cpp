#include "solver/tree_system.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <utility>

#include "solver/four_doubles.hpp"

namespace softstep::solver {

namespace {

// A node id: body b is b, joint j is bodies + j.
struct Graph {
  std::uint32_t bodies;
  const std::vector<TreeJoint>& joints;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> around;  // per body

  bool is_joint(std::uint32_t node) const { return node >= bodies; }
  // Calls visit(neighbour, side) for every neighbour of `node`; side is the end of the joint
  // (the node or the neighbour) at the body.
  template <class Visit>
  void neighbours(std::uint32_t node, Visit visit) const {
    if (!is_joint(node)) {
      for (const auto& [joint, side] : around[node]) visit(joint, side);
      return;
    }
    const TreeJoint& j = joints[node - bodies];
    for (std::uint8_t s = 0; s < 2; ++s) {
      if (j.body[s] >= 0) visit(static_cast<std::uint32_t>(j.body[s]), s);
    }
  }
};

// Breadth first from `root`: the nodes in the order reached, each with the position of its
// parent (-1 for the root) and the side of the edge to it.
struct Reached {
  std::vector<std::uint32_t> node;
  std::vector<std::int32_t> parent;
  std::vector<std::uint8_t> side;
};

Reached breadth_first(const Graph& g, std::uint32_t root, std::uint32_t nodes) {
  Reached r;
  r.node.reserve(nodes);
  std::vector<bool> seen(nodes, false);
  r.node.push_back(root);
  r.parent.push_back(-1);
  r.side.push_back(0);
  seen[root] = true;
  for (std::size_t k = 0; k < r.node.size(); ++k) {
    g.neighbours(r.node[k], [&](std::uint32_t next, std::uint8_t side) {
      if (seen[next]) return;
      seen[next] = true;
      r.node.push_back(next);
      r.parent.push_back(static_cast<std::int32_t>(k));
      r.side.push_back(side);
    });
  }
  return r;
}

// Per position of `r`, the number of nodes in its subtree.
std::vector<std::uint32_t> subtree_sizes(const Reached& r) {
  std::vector<std::uint32_t> size(r.node.size(), 1);
  for (std::size_t k = r.node.size(); k-- > 1;) {
    size[static_cast<std::size_t>(r.parent[k])] += size[k];
  }
  return size;
}

// An island's elimination order: [part 0 below the root's children][part 1 below them][the
// root's children of part 0][of part 1][the root], `start` of each of the five groups; and per
// body and joint its part.
struct Layout {
  std::vector<TreeNode> order;
  std::size_t start[5] = {};
  std::vector<std::uint8_t> body_part, joint_part;
};

// The order from `root`, the tree below it split in two parts when `split`. Empty when not
// every node is reached (not connected).
Layout lay_out(const Graph& g, std::uint32_t root, bool split) {
  const std::uint32_t nodes = g.bodies + static_cast<std::uint32_t>(g.joints.size());
  const Reached r = breadth_first(g, root, nodes);
  Layout out;
  if (r.node.size() != nodes) return out;
  // Per position its part: the root's children go to the lighter part, heaviest first (ties
  // in breadth-first order), and every other node to its top ancestor's.
  std::vector<std::uint8_t> part(nodes, 0);
  if (split) {
    const std::vector<std::uint32_t> size = subtree_sizes(r);
    std::vector<std::size_t> tops;
    for (std::size_t k = 1; k < nodes && r.parent[k] == 0; ++k) tops.push_back(k);
    std::stable_sort(tops.begin(), tops.end(),
                     [&](std::size_t a, std::size_t b) { return size[a] > size[b]; });
    std::uint32_t load[2] = {0, 0};
    for (std::size_t t : tops) {
      part[t] = load[1] < load[0] ? 1 : 0;
      load[part[t]] += size[t];
    }
    for (std::size_t k = 1; k < nodes; ++k) {
      if (r.parent[k] != 0) part[k] = part[static_cast<std::size_t>(r.parent[k])];
    }
  }
  // Leaves first (the breadth-first order reversed), grouped stably: [part 0 below the tops]
  // [part 1 below the tops][part 0's tops][part 1's tops][the root]. A node's children are in
  // its group or an earlier one, in the same relative order as before grouping.
  const auto group = [&](std::size_t k) {
    if (k == 0) return 4;
    return (r.parent[k] == 0 ? 2 : 0) + part[k];
  };
  std::size_t count[5] = {};
  for (std::size_t k = 0; k < nodes; ++k) ++count[group(k)];
  std::size_t start[5] = {0};
  for (int i = 1; i < 5; ++i) start[i] = start[i - 1] + count[i - 1];
  std::copy(start, start + 5, out.start);
  std::vector<std::int32_t> position(nodes);
  std::size_t next[5];
  std::copy(start, start + 5, next);
  for (std::size_t k = nodes; k-- > 0;) position[k] = static_cast<std::int32_t>(next[group(k)]++);
  out.order.resize(nodes);
  out.body_part.assign(g.bodies, 0);
  out.joint_part.assign(g.joints.size(), 0);
  for (std::size_t k = 0; k < nodes; ++k) {
    TreeNode n;
    n.joint = g.is_joint(r.node[k]);
    n.index = n.joint ? r.node[k] - g.bodies : r.node[k];
    n.parent = r.parent[k] < 0 ? -1 : position[static_cast<std::size_t>(r.parent[k])];
    n.side = r.side[k];
    out.order[static_cast<std::size_t>(position[k])] = n;
    (n.joint ? out.joint_part[n.index] : out.body_part[n.index]) = part[k];
  }
  return out;
}

}  // namespace

void set_ball_arms(TreeJoint& joint) {
  for (int side = 0; side < 2; ++side) {
    const double* j = joint.jacobian[side].data();  // col-major: (i, c) at i + 3 c
    joint.arm[side][0] = j[2 + 3 * 4];
    joint.arm[side][1] = j[0 + 3 * 5];
    joint.arm[side][2] = j[1 + 3 * 3];
    joint.arm[side][3] = 0.0;
  }
}

bool TreeSystem::build(std::uint32_t bodies, const std::vector<TreeJoint>& joints) {
  order_.clear();
  if (bodies == 0) return false;
  const std::uint32_t nodes = bodies + static_cast<std::uint32_t>(joints.size());
  Graph g{bodies, joints, std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>>(bodies)};
  std::size_t edges = 0;
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    for (std::uint8_t s = 0; s < 2; ++s) {
      const std::int32_t b = joints[j].body[s];
      if (b < 0) continue;
      g.around[static_cast<std::size_t>(b)].push_back({bodies + j, s});
      ++edges;
    }
  }
  if (edges + 1 != nodes) return false;  // a connected graph is a tree iff edges = nodes - 1
  // A joint on one movable body (its other end static or kinematic) has the block -Gamma, 0
  // for a rigid row: it cannot be eliminated alone. It can be the root, or a leaf under a chain
  // link (its body's only child), eliminated with the link in joint space (E = J W J^T is
  // invertible). An island can have one: two (a bridge pinned at both ends) close a loop
  // through the ground, and the island stays iterative.
  std::int32_t grounded = -1;
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    if (joints[j].body[0] >= 0 && joints[j].body[1] >= 0) continue;
    if (grounded >= 0) return false;
    grounded = static_cast<std::int32_t>(j);
  }
  // Without a grounded joint the root is body 0, and every joint has a child body.
  std::uint32_t root = grounded >= 0 ? bodies + static_cast<std::uint32_t>(grounded) : 0;
  bool split = false;
  if (joints.size() >= kSplitJoints) {
    // The centre: the node whose largest remaining piece, once it is taken out, is smallest
    // (the first such in breadth-first order from body 0). Rooted there the tree's two halves
    // are eliminated independently, on two threads when one island is most of a step's work.
    const Reached from_zero = breadth_first(g, 0, nodes);
    if (from_zero.node.size() != nodes) return false;  // not connected
    const std::vector<std::uint32_t> size = subtree_sizes(from_zero);
    std::vector<std::uint32_t> heaviest(nodes, 0);
    for (std::size_t k = 1; k < nodes; ++k) {
      const auto p = static_cast<std::size_t>(from_zero.parent[k]);
      heaviest[p] = std::max(heaviest[p], size[k]);
    }
    std::size_t centre = 0;
    std::uint32_t best = nodes;
    for (std::size_t k = 0; k < nodes; ++k) {
      const std::uint32_t piece = std::max(heaviest[k], nodes - size[k]);
      if (piece < best) {
        best = piece;
        centre = k;
      }
    }
    const std::uint32_t centre_node = from_zero.node[centre];
    if (grounded < 0) {
      root = centre_node;
      split = true;
    } else {
      // With a grounded joint the root is a joint on the path from it to the centre, the
      // nearest the centre with only chain links (bodies of two joints) between it and the
      // grounded joint. Rooted elsewhere, a joint between the grounded end and the root would
      // be inverted alone, and a half held at one end can be rigid along a direction (a
      // straight chain along its axis): its block singular. Folded into chain links up to a
      // root joint, whose other side moves freely, every pivot stays invertible.
      const Reached from_centre = breadth_first(g, centre_node, nodes);
      std::vector<std::size_t> at(nodes);
      for (std::size_t k = 0; k < nodes; ++k) at[from_centre.node[k]] = k;
      std::size_t k = at[bodies + static_cast<std::uint32_t>(grounded)];
      while (from_centre.parent[k] >= 0) {
        k = static_cast<std::size_t>(from_centre.parent[k]);
        const std::uint32_t node = from_centre.node[k];
        if (!g.is_joint(node)) {
          if (g.around[node].size() != 2) break;
          continue;
        }
        root = node;
        split = true;
      }
    }
  }
  Layout layout = lay_out(g, root, split);
  if (layout.order.empty()) return false;  // not connected
  order_ = std::move(layout.order);
  segment_[0] = {layout.start[0], layout.start[1]};
  segment_[1] = {layout.start[1], layout.start[2]};
  tops_[0] = {layout.start[2], layout.start[3]};
  tops_[1] = {layout.start[3], layout.start[4]};
  body_part_ = std::move(layout.body_part);
  joint_part_ = std::move(layout.joint_part);
  body_block_.resize(bodies);
  body_transfer_.resize(bodies);
  std::apply([&](auto&... sides) { (sides.resize(bodies), ...); }, body_rhs_);
  joint_block_.resize(joints.size());
  joint_inverse_.resize(joints.size());
  std::apply([&](auto&... sides) { (sides.resize(joints.size()), ...); }, joint_rhs_);
  body_child_.assign(bodies, kNoChild);
  body_child_side_.assign(bodies, 0);
  link_e_inverse_.resize(bodies);
  link_y_.resize(bodies);
  for (const TreeNode& n : order_) {
    if (!n.joint || n.parent < 0) continue;
    const std::uint32_t body = order_[static_cast<std::size_t>(n.parent)].index;
    body_child_[body] =
        body_child_[body] == kNoChild ? static_cast<std::int32_t>(n.index) : kManyChildren;
    body_child_side_[body] = n.side;
  }
  // A body that is not a chain link between ball joints reads its joints' blocks.
  std::vector<bool> reads_its_blocks(bodies, false);
  for (const TreeNode& n : order_) {
    if (!n.joint) reads_its_blocks[n.index] = !is_link(n) || !ball_link(n, joints);
  }
  reads_blocks_.assign(joints.size(), 0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    bool reads = !joints[j].ball;
    for (const std::int32_t b : joints[j].body) {
      reads = reads || (b >= 0 && reads_its_blocks[static_cast<std::size_t>(b)]);
    }
    reads_blocks_[j] = reads ? 1 : 0;
  }
  return true;
}

namespace {

using Mat63 = Eigen::Matrix<double, 6, 3>;

// B^-1 of a reduced body block, B = [A C; C^T D] in 3x3 blocks (linear, then angular): A is
// m I plus what child joints add, D the inertia plus theirs, both positive definite, so is
// the Schur complement S = D - C^T A^-1 C. Two 3x3 inverses (cofactors) and four 3x3 products,
// all fixed-size and inlined: Eigen's LLT<Mat6> ran its factor and its triangular solves
// through the dynamic-size kernels, half of the exact pass's time (perf, the 1,000-link whip,
// when its links were eliminated here too; now only bodies of many children are).
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

// A chain link's products, in the factor and in the solve, as multiply-adds of a row of three
// doubles (and a zero) by a broadcast scalar, four-wide with AVX. Eigen's fixed-size 3x3 and
// 6x3 products run two-wide with shuffles here (EIGEN_MAX_ALIGN_BYTES is 16 project-wide).
using Row3 = FourDoubles;

// A row of `matrix` (col-major, `stride` between columns).
[[gnu::always_inline]] inline Row3 row_of(const double* matrix, int row, int stride) {
  return Row3{matrix[row], matrix[row + stride], matrix[row + 2 * stride], 0.0};
}

// sum_k a[k] * rows[k], k < 3 (fused, multiply_add)
[[gnu::always_inline]] inline Row3 combine(const Row3& a, const Row3* rows) {
  return multiply_add(a[2], rows[2], multiply_add(a[1], rows[1], a[0] * rows[0]));
}

// sum + sum_k a[k] * rows[k], k < 3 (fused, multiply_add)
[[gnu::always_inline]] inline Row3 combine_onto(const Row3& a, const Row3* rows, const Row3& sum) {
  return multiply_add(a[2], rows[2], multiply_add(a[1], rows[1], multiply_add(a[0], rows[0], sum)));
}

// The transpose of a 3x3 block's rows (their last elements 0): its columns, in registers.
[[gnu::always_inline]] inline void transpose(const Row3 (&rows)[3], Row3 (&columns)[3]) {
  const Row3 even = __builtin_shufflevector(rows[0], rows[1], 0, 4, 2, 6);  // a0 b0 a2 b2
  const Row3 odd = __builtin_shufflevector(rows[0], rows[1], 1, 5, 3, 7);   // a1 b1 a3 b3
  columns[0] = __builtin_shufflevector(even, rows[2], 0, 1, 4, 7);
  columns[1] = __builtin_shufflevector(odd, rows[2], 0, 1, 5, 7);
  columns[2] = __builtin_shufflevector(even, rows[2], 2, 3, 6, 7);
}

// A 3x3 inverse by cofactors, by columns: column k of the adjugate is the cross product of the
// two rows other than k (in turn), its element i the cofactor of (k, i). Three vector cross
// products where the cofactors one by one took nine scalar differences and the inserts that
// built rows of them.
[[gnu::always_inline]] inline void invert_columns(const Row3 (&e)[3], Row3 (&columns)[3]) {
  const Row3 c0 = cross(e[1], e[2]), c1 = cross(e[2], e[0]), c2 = cross(e[0], e[1]);
  const double s =
      1.0 / multiply_add(e[0][2], c0[2], multiply_add(e[0][1], c0[1], e[0][0] * c0[0]));
  columns[0] = c0 * s;
  columns[1] = c1 * s;
  columns[2] = c2 * s;
}

// A ball joint's rows against one body, J = [s I, [a]x] (s = -1 on side a, +1 on side b; a =
// -s r for the anchor's arm r: TreeJoint::ball), read back from the block: s and a.
struct BallSide {
  double s = 0.0;
  Row3 a{};
};

[[gnu::always_inline]] inline BallSide ball_side(const TreeJoint& joint, int side) {
  return {side == 0 ? -1.0 : 1.0, load4(joint.arm[side])};
}

// The columns of I_w [a]x, I_w (a x e_k): two of I_w's columns each (I_w symmetric: its rows).
[[gnu::always_inline]] inline void inertia_times_skew(const Row3 (&inertia_w)[3], const Row3& a,
                                                      Row3 (&c)[3]) {
  c[0] = multiply_add(a[2], inertia_w[1], -(a[1] * inertia_w[2]));
  c[1] = multiply_add(a[0], inertia_w[2], -(a[2] * inertia_w[0]));
  c[2] = multiply_add(a[1], inertia_w[0], -(a[0] * inertia_w[1]));
}

// The columns of J_x W J_y^T = s_x s_y w I - [a_x]x I_w [a_y]x for ball sides x and y, from
// x's arm and c = I_w [a_y]x by columns (inertia_times_skew); sw = s_x s_y w.
[[gnu::always_inline]] inline void ball_products(const BallSide& x, double sw, const Row3 (&c)[3],
                                                 Row3 (&k)[3]) {
  for (int column = 0; column < 3; ++column) {
    Row3 diagonal{0.0, 0.0, 0.0, 0.0};
    diagonal[column] = sw;
    k[column] = diagonal - cross(x.a, c[column]);
  }
}

// U = W J^T by rows for W = diag(w I, I_w): w times J's linear columns, then I_w times its
// angular ones.
[[gnu::always_inline]] inline void times_inverse_mass(double w, const Row3 (&inertia_w)[3],
                                                      const Jac& jac, Row3 (&u)[6]) {
  const double* j = jac.data();
  const Row3 angular[3] = {load3(j + 9), load3(j + 12), load3(j + 15)};
  for (int k = 0; k < 3; ++k) u[k] = w * load3(j + 3 * k);
  for (int i = 0; i < 3; ++i) u[3 + i] = combine(inertia_w[i], angular);
}

// K = J U by rows (J 3x6, U 6x3 by rows).
[[gnu::always_inline]] inline void jacobian_times(const Jac& jac, const Row3 (&u)[6],
                                                  Row3 (&k)[3]) {
  const double* j = jac.data();
  for (int i = 0; i < 3; ++i) {
    k[i] = j[i] * u[0];
    for (int c = 1; c < 6; ++c) k[i] = multiply_add(j[i + 3 * c], u[c], k[i]);
  }
}

// J's rows (J 3x6 col-major), each as a linear half (rows[0..2]) and an angular half
// (rows[3..5]).
[[gnu::always_inline]] inline void jacobian_rows(const Jac& jac, Row3 (&rows)[6]) {
  for (int k = 0; k < 3; ++k) {
    rows[k] = row_of(jac.data(), k, 3);
    rows[3 + k] = row_of(jac.data() + 9, k, 3);
  }
}

// A chain link's products K_xy = J_x W J_y^T with its parent joint p and child joint c (the
// sides at the link), by rows, each formed where the elimination first needs it: K_pp, K_cc,
// then K_cp and its columns (eliminate_link).
// From the general 3x6 blocks: U = W J^T, then J U.
struct GeneralLinkProducts {
  double w;
  const Row3 (&inertia_w)[3];
  const Jac* parent;
  const Jac* child;
  Row3 u_p[6] = {};

  [[gnu::always_inline]] void parent_products(Row3 (&k_pp)[3]) {
    times_inverse_mass(w, inertia_w, *parent, u_p);
    jacobian_times(*parent, u_p, k_pp);
  }
  [[gnu::always_inline]] void child_products(Row3 (&k_cc)[3]) {
    Row3 u_c[6];
    times_inverse_mass(w, inertia_w, *child, u_c);
    jacobian_times(*child, u_c, k_cc);
  }
  [[gnu::always_inline]] void across_products(Row3 (&k_cp)[3], Row3 (&k_cp_columns)[3]) {
    jacobian_times(*child, u_p, k_cp);
    transpose(k_cp, k_cp_columns);
  }
};

// Between ball joints (TreeJoint::ball), from their signs and arms: s_x s_y w I - [a_x]x I_w
// [a_y]x, a third of the general products' operations (the factor of 1,000 links 8 % cheaper,
// the whip's exact step 5 %, Zen 5). K_pp and K_cc are symmetric: their columns serve as their
// rows; K_cp's rows are K_pc's columns.
struct BallLinkProducts {
  double w;
  const Row3 (&inertia_w)[3];
  BallSide p, c;  // the parent joint's side and the child joint's (those the link has)
  Row3 c_p[3] = {}, c_c[3] = {};

  [[gnu::always_inline]] void parent_products(Row3 (&k_pp)[3]) {
    inertia_times_skew(inertia_w, p.a, c_p);
    ball_products(p, w, c_p, k_pp);
  }
  [[gnu::always_inline]] void child_products(Row3 (&k_cc)[3]) {
    inertia_times_skew(inertia_w, c.a, c_c);
    ball_products(c, w, c_c, k_cc);
  }
  // K_pc = K_cp^T (I_w symmetric): K_cp's rows transposed in registers, where a second set of
  // three cross products (from c_p) formed its columns before 2026-11-29: the same to
  // rounding (on the whip's sphere links to the last bit), and with E^-1 read by columns for
  // its rows below, the whip's exact step 1.3 % cheaper (Zen 5).
  [[gnu::always_inline]] void across_products(Row3 (&k_cp)[3], Row3 (&k_cp_columns)[3]) {
    ball_products(p, p.s * c.s * w, c_c, k_cp);
    transpose(k_cp, k_cp_columns);
  }
};

// A chain link's forward step, for each of Columns right sides: its parent joint's side r_p
// loses y^T r_c (none at the root, r_p null), then its child joint's r_c becomes g = E^-1 r_c
// (e_columns: E^-1 by columns). Each right side's three doubles are loaded once: the stores
// may alias y and E^-1 for the compiler.
template <int Columns>
[[gnu::always_inline]] inline void link_forward(double* r_c, double* r_p, const Row3* y_rows,
                                                const Row3 (&e_columns)[3]) {
  for (int column = 0; column < Columns; ++column) {
    const Row3 r = load3(r_c + 3 * column);
    if (r_p != nullptr) store3(r_p + 3 * column, load3(r_p + 3 * column) - combine(r, y_rows));
    store3(r_c + 3 * column, combine(r, e_columns));
  }
}

// The rows of a 3x3 block subtracted from a block of padded rows (their last elements 0).
[[gnu::always_inline]] inline void subtract_rows(const Row3 (&rows)[3], double (&block)[3][4]) {
  for (int i = 0; i < 3; ++i) store4(block[i], load4(block[i]) - rows[i]);
}

}  // namespace

void TreeSystem::init_blocks(Span span, const std::vector<InverseMass>& inverse_mass,
                             const std::vector<TreeJoint>& joints) {
  // The blocks of H; each becomes its reduced block's inverse when its node is eliminated. A
  // body of many children sums M and their terms; a chain link reads W = M^-1.
  for (std::size_t k = span.begin; k < span.end; ++k) {
    const TreeNode& node = order_[k];
    if (!node.joint) {
      if (body_child_[node.index] != kManyChildren) continue;
      Mat6& block = body_block_[node.index];
      block.setZero();
      block.topLeftCorner<3, 3>().diagonal().setConstant(inverse_mass[node.index].linear);
      block.bottomRightCorner<3, 3>() = inverse_mass[node.index].angular;
      invert_body_block(block);
      continue;
    }
    const TreeJoint& joint = joints[node.index];
    if (joint.rows == 3) {
      // -Gamma by rows (Gamma symmetric: its columns), a vector each
      for (int r = 0; r < 3; ++r) {
        store4(joint_block_[node.index].v[r], -load3(joint.gamma.data() + 3 * r));
      }
      continue;
    }
    Eigen::Matrix3d d = -joint.gamma;
    for (int r = joint.rows; r < 3; ++r) {
      d.row(r).setZero();
      d.col(r).setZero();
      d(r, r) = -1.0;
    }
    PaddedRows(joint_block_[node.index].v[0]) = d;
  }
}

template <int Columns>
void TreeSystem::eliminate(Span span, const InverseMass* inverse_mass,
                           const std::vector<TreeJoint>& joints) {
  // Leaves first: fold each node into its parent (a Schur complement), no fill on a tree;
  // with right sides, each node's forward step right after its elimination (a chain link's
  // inside eliminate_link, from its E^-1 and y in registers).
  for (std::size_t k = span.begin; k < span.end; ++k) {
    if (is_link(order_[k])) {
      eliminate_link<Columns>(k, inverse_mass, joints);
      continue;
    }
    eliminate_node(k, joints);
    if constexpr (Columns > 0) forward_node<Columns>(k, joints);
  }
}

void TreeSystem::eliminate_node(std::size_t k, const std::vector<TreeJoint>& joints) {
  const TreeNode& node = order_[k];
  if (node.joint) {
    if (under_link(node)) return;  // folded with its link (eliminate_link)
    // Reduced joint blocks are negative definite (or -1 padding): a 3x3 inverse.
    joint_inverse_[node.index] = PaddedRows(joint_block_[node.index].v[0]).inverse();
    if (node.parent < 0) return;
    const std::uint32_t body = order_[static_cast<std::size_t>(node.parent)].index;
    const Jac& jac = joints[node.index].jacobian[node.side];  // E = J^T, 6x3
    const Jac scaled = joint_inverse_[node.index] * jac;
    body_block_[body].noalias() -= jac.transpose() * scaled;
    return;
  }
  // B = M + sum of J_c^T (-D_c^-1) J_c over the children, positive definite.
  Mat6& inverse = body_block_[node.index];
  invert_body_block(inverse);
  if (node.parent < 0) return;
  const std::uint32_t parent_joint = order_[static_cast<std::size_t>(node.parent)].index;
  const Jac& parent_jac = joints[parent_joint].jacobian[node.side];
  Mat63& transfer = body_transfer_[node.index];
  transfer.noalias() = inverse * parent_jac.transpose();
  PaddedRows(joint_block_[parent_joint].v[0]).noalias() -= parent_jac * transfer;
}

void TreeSystem::init_part_blocks(int part, const std::vector<InverseMass>& inverse_mass,
                                  const std::vector<TreeJoint>& joints) {
  // The part's tops are reduced by its nodes (their children): their blocks start here, and
  // part 0 starts the root's (its children's sums come in the root part).
  init_blocks(segment_[part], inverse_mass, joints);
  init_blocks(tops_[part], inverse_mass, joints);
  if (part == 0) init_blocks(root_node(), inverse_mass, joints);
}

void TreeSystem::factor_part(int part, const std::vector<InverseMass>& inverse_mass,
                             const std::vector<TreeJoint>& joints) {
  init_part_blocks(part, inverse_mass, joints);
  eliminate<0>(segment_[part], inverse_mass.data(), joints);
}

void TreeSystem::factor_root(const std::vector<InverseMass>& inverse_mass,
                             const std::vector<TreeJoint>& joints) {
  inverse_mass_ = inverse_mass.data();
  eliminate<0>(root_part(), inverse_mass.data(), joints);
}

void TreeSystem::factor(const std::vector<InverseMass>& inverse_mass,
                        const std::vector<TreeJoint>& joints) {
  factor_part(0, inverse_mass, joints);
  factor_part(1, inverse_mass, joints);
  factor_root(inverse_mass, joints);
}

template <int Columns, class Products>
[[gnu::always_inline]] inline void TreeSystem::eliminate_link_with(const TreeNode& node,
                                                                   Products& products) {
  Padded3* parent_block = nullptr;
  Row3 k_pp[3];
  if (node.parent >= 0) {
    parent_block = &joint_block_[order_[static_cast<std::size_t>(node.parent)].index];
    products.parent_products(k_pp);
  }
  const std::int32_t child = body_child_[node.index];
  if (child == kNoChild) {
    if (parent_block != nullptr) subtract_rows(k_pp, parent_block->v);
    return;  // a leaf link has no forward step
  }
  Row3 e[3], e_inverse[3];  // E^-1 by columns
  products.child_products(e);
  const Padded3& child_block = joint_block_[static_cast<std::size_t>(child)];
  for (int i = 0; i < 3; ++i) e[i] -= load4(child_block.v[i]);
  invert_columns(e, e_inverse);
  for (int i = 0; i < 3; ++i) store4(link_e_inverse_[node.index].v[i], e_inverse[i]);
  double* r_c = nullptr;
  if constexpr (Columns > 0) r_c = joint_rhs<Columns>()[static_cast<std::size_t>(child)].data();
  if (parent_block == nullptr) {
    link_forward<Columns>(r_c, nullptr, nullptr, e_inverse);
    return;
  }
  Row3 k_cp[3], k_cp_columns[3], y[3];
  products.across_products(k_cp, k_cp_columns);
  // y's row i from E^-1's row i, which is its column i: E is symmetric (K_cc, Gamma and the
  // reduced blocks are), so its adjugate by cross products is too, to rounding.
  for (int i = 0; i < 3; ++i) y[i] = combine(e_inverse[i], k_cp);
  Row3 y_columns[3];
  transpose(y, y_columns);
  for (int i = 0; i < 3; ++i) store4(link_y_[node.index].v[i], y_columns[i]);
  Row3 left[3];
  for (int i = 0; i < 3; ++i) left[i] = k_pp[i] - combine(k_cp_columns[i], y);
  subtract_rows(left, parent_block->v);
  if constexpr (Columns > 0) {
    double* r_p = joint_rhs<Columns>()[order_[static_cast<std::size_t>(node.parent)].index].data();
    link_forward<Columns>(r_c, r_p, y, e_inverse);
  }
}

// A chain link: a body b of at most one child joint c, eliminated together with c in joint
// space. From b's rows, v_b = W (f_b - J_c^T l_c - J_p^T l_p) (W = M^-1; f_b = 0: a body's right
// side starts at 0 and only a joint under a body of many children adds to it), so c's rows
// J_c v_b + D_c l_c = s_c (s_c: c's right side -r_c, already reduced by c's own child) give
//   l_c = -E^-1 (s_c + K_cp l_p),  E = K_cc - D_c,  K_xy = J_x W J_y^T,
// and the parent joint p's block loses K_pp - K_cp^T y and its right side y^T s_c, with
// y = E^-1 K_cp (y^T = K_pc E^-1 because E is symmetric: Gamma and I_w are): block-tridiagonal
// elimination along a chain, one dependent 3x3 inverse per link. Kept: E^-1 and, below a
// parent, y. W is diag(w I, I_w) (the solver's mass record): its zero blocks are not
// multiplied.
template <int Columns>
void TreeSystem::eliminate_link(std::size_t k, const InverseMass* inverse_mass,
                                const std::vector<TreeJoint>& joints) {
  const TreeNode& node = order_[k];
  const InverseMass& mass = inverse_mass[node.index];
  // I_w is symmetric: its rows are its columns.
  const double* angular = mass.angular.data();
  const Row3 inertia_w[3] = {load3(angular), load3(angular + 3), load3(angular + 6)};
  const TreeJoint* parent_joint =
      node.parent >= 0 ? &joints[order_[static_cast<std::size_t>(node.parent)].index] : nullptr;
  const std::int32_t child = body_child_[node.index];
  const TreeJoint* child_joint =
      child == kNoChild ? nullptr : &joints[static_cast<std::size_t>(child)];
  const int child_side = body_child_side_[node.index];
  if (ball_link(node, joints)) {
    BallLinkProducts products{
        mass.linear, inertia_w,
        parent_joint != nullptr ? ball_side(*parent_joint, node.side) : BallSide{},
        child_joint != nullptr ? ball_side(*child_joint, child_side) : BallSide{}};
    eliminate_link_with<Columns>(node, products);
  } else {
    const Jac* parent_jac = parent_joint != nullptr ? &parent_joint->jacobian[node.side] : nullptr;
    const Jac* child_jac = child_joint != nullptr ? &child_joint->jacobian[child_side] : nullptr;
    GeneralLinkProducts products{mass.linear, inertia_w, parent_jac, child_jac};
    eliminate_link_with<Columns>(node, products);
  }
}

template <int Columns>
std::vector<Eigen::Matrix<double, 6, Columns>>& TreeSystem::body_rhs() {
  return std::get<Columns - 1>(body_rhs_);
}

template <int Columns>
std::vector<Eigen::Matrix<double, 3, Columns>>& TreeSystem::joint_rhs() {
  return std::get<Columns - 1>(joint_rhs_);
}

template <int Columns>
void TreeSystem::init_rhs(Span span, const std::vector<TreeJoint>& joints, const MoreSides& more) {
  // Only a body of many children has a right side of its own (a chain link's is folded into
  // its joints'): the others are neither read nor cleared.
  auto& bodies = body_rhs<Columns>();
  auto& rhs = joint_rhs<Columns>();
  for (std::size_t k = span.begin; k < span.end; ++k) {
    const TreeNode& node = order_[k];
    if (!node.joint) {
      if (body_child_[node.index] == kManyChildren) bodies[node.index].setZero();
      continue;
    }
    const std::size_t j = node.index;
    rhs[j].col(0) = -joints[j].residual;
    for (int c = 1; c < Columns; ++c) rhs[j].col(c) = -(*more[static_cast<std::size_t>(c - 1)])[j];
    for (int r = joints[j].rows; r < 3; ++r) rhs[j].row(r).setZero();
  }
}

template <int Columns>
void TreeSystem::forward(Span span, const std::vector<TreeJoint>& joints) {
  // Leaves first. A link's child joint keeps g = E^-1 r_c in its right side.
  for (std::size_t k = span.begin; k < span.end; ++k) forward_node<Columns>(k, joints);
}

template <int Columns>
void TreeSystem::forward_node(std::size_t k, const std::vector<TreeJoint>& joints) {
  using JointColumns = Eigen::Matrix<double, 3, Columns>;
  auto& body_rhs = this->body_rhs<Columns>();
  auto& joint_rhs = this->joint_rhs<Columns>();
  const TreeNode& node = order_[k];
  const bool root = node.parent < 0;
  if (node.joint) {
    if (root || under_link(node)) return;
    const TreeNode& parent = order_[static_cast<std::size_t>(node.parent)];
    const Jac& jac = joints[node.index].jacobian[node.side];
    const JointColumns scaled = joint_inverse_[node.index] * joint_rhs[node.index];
    body_rhs[parent.index].noalias() -= jac.transpose() * scaled;
  } else if (is_link(node)) {
    const std::int32_t child = body_child_[node.index];
    if (child == kNoChild) return;
    // The factor's E^-1 and y as eliminate_link left them (a root link has no y).
    const Padded3& e = link_e_inverse_[node.index];
    const Row3 e_columns[3] = {load4(e.v[0]), load4(e.v[1]), load4(e.v[2])};
    Row3 y_rows[3] = {};
    if (!root) {
      const Padded3& y = link_y_[node.index];
      const Row3 y_columns[3] = {load4(y.v[0]), load4(y.v[1]), load4(y.v[2])};
      transpose(y_columns, y_rows);
    }
    double* r_p =
        root ? nullptr : joint_rhs[order_[static_cast<std::size_t>(node.parent)].index].data();
    link_forward<Columns>(joint_rhs[static_cast<std::size_t>(child)].data(), r_p, y_rows,
                          e_columns);
  } else if (!root) {
    const std::uint32_t parent_joint = order_[static_cast<std::size_t>(node.parent)].index;
    joint_rhs[parent_joint].noalias() -=
        body_transfer_[node.index].transpose() * body_rhs[node.index];
  }
}

template <int Columns>
void TreeSystem::backward(Span span, const std::vector<TreeJoint>& joints,
                          std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                          std::vector<Eigen::Matrix<double, 3, Columns>>& dp) {
  using JointColumns = Eigen::Matrix<double, 3, Columns>;
  using BodyColumns = Eigen::Matrix<double, 6, Columns>;
  const auto& body_rhs = this->body_rhs<Columns>();
  const auto& joint_rhs = this->joint_rhs<Columns>();
  // Root first: every node from its parent's solution. A joint's unknown is lambda = -dP, and
  // dp keeps dP: each lambda stored negated and read back negated (exact, and a pass over the
  // joints to negate them afterwards saved: 1 % of the whip's exact step, Zen 5).
  for (std::size_t k = span.end; k-- > span.begin;) {
    const TreeNode& node = order_[k];
    const bool root = node.parent < 0;
    const std::uint32_t parent = root ? 0 : order_[static_cast<std::size_t>(node.parent)].index;
    if (node.joint) {
      if (under_link(node)) continue;  // solved with its link
      if (root) {
        dp[node.index].noalias() = -(joint_inverse_[node.index] * joint_rhs[node.index]);
        continue;
      }
      const Jac& jac = joints[node.index].jacobian[node.side];
      const JointColumns rhs = joint_rhs[node.index] - jac * dv[parent];
      dp[node.index].noalias() = -(joint_inverse_[node.index] * rhs);
    } else if (is_link(node)) {
      // l_c = -g - y l_p, then v_b = -W (J_c^T l_c + J_p^T l_p).
      const std::int32_t child = body_child_[node.index];
      const bool has_child = child != kNoChild;
      const auto c = static_cast<std::size_t>(child);
      // J^T l = sum_k l[k] (row k of J), each row in a linear and an angular half, loaded
      // once for every right side; for a ball joint's rows s [I, [a]x], (s l, l x a) from its
      // sign and arm (TreeJoint::ball: the whip's exact step 0.535 -> 0.507 ms, Zen 5).
      const bool ball = ball_link(node, joints);
      Row3 parent_rows[6] = {}, child_rows[6] = {}, y_columns[3] = {};
      BallSide parent_ball, child_ball;
      if (!root) {
        if (ball) {
          parent_ball = ball_side(joints[parent], node.side);
        } else {
          jacobian_rows(joints[parent].jacobian[node.side], parent_rows);
        }
      }
      if (has_child) {
        const int side = body_child_side_[node.index];
        if (ball) {
          child_ball = ball_side(joints[c], side);
        } else {
          jacobian_rows(joints[c].jacobian[side], child_rows);
        }
      }
      if (has_child && !root) {
        for (int i = 0; i < 3; ++i) y_columns[i] = load4(link_y_[node.index].v[i]);
      }
      const double w = inverse_mass_[node.index].linear;
      const double* inertia = inverse_mass_[node.index].angular.data();
      const Row3 inertia_columns[3] = {load3(inertia), load3(inertia + 3), load3(inertia + 6)};
      for (int column = 0; column < Columns; ++column) {
        Row3 linear{}, angular{}, l_p{};
        if (!root) {
          l_p = -load3(dp[parent].data() + 3 * column);
          if (ball) {
            linear = parent_ball.s * l_p;
            angular = cross(l_p, parent_ball.a);  // l x a = -[a]x l
          } else {
            linear += combine(l_p, parent_rows);
            angular += combine(l_p, parent_rows + 3);
          }
        }
        if (has_child) {
          Row3 l = -load3(joint_rhs[c].data() + 3 * column);
          if (!root) l -= combine(l_p, y_columns);
          store3(dp[c].data() + 3 * column, -l);
          if (ball) {
            linear = multiply_add(child_ball.s, l, linear);
            angular += cross(l, child_ball.a);
          } else {
            linear = combine_onto(l, child_rows, linear);
            angular = combine_onto(l, child_rows + 3, angular);
          }
        }
        double* v = dv[node.index].data() + 6 * column;
        store3(v, -w * linear);
        store3(v + 3, -combine(angular, inertia_columns));
      }
    } else {
      BodyColumns rhs = body_rhs[node.index];
      if (!root) rhs.noalias() += joints[parent].jacobian[node.side].transpose() * dp[parent];
      dv[node.index].noalias() = body_block_[node.index] * rhs;
    }
  }
}

template <int Columns>
void TreeSystem::init_part_rhs(int part, const std::vector<TreeJoint>& joints,
                               const MoreSides& more) {
  // The part's tops take its nodes' right sides, and part 0 starts the root's (its children's
  // sums come in the root part).
  init_rhs<Columns>(segment_[part], joints, more);
  init_rhs<Columns>(tops_[part], joints, more);
  if (part == 0) init_rhs<Columns>(root_node(), joints, more);
}

template <int Columns>
void TreeSystem::solve_up(int part, const std::vector<TreeJoint>& joints, const MoreSides& more) {
  init_part_rhs<Columns>(part, joints, more);
  forward<Columns>(segment_[part], joints);
}

template <int Columns>
void TreeSystem::factor_solve_up(int part, const std::vector<InverseMass>& inverse_mass,
                                 const std::vector<TreeJoint>& joints, const MoreSides& more) {
  init_part_blocks(part, inverse_mass, joints);
  init_part_rhs<Columns>(part, joints, more);
  eliminate<Columns>(segment_[part], inverse_mass.data(), joints);
}

template <int Columns>
void TreeSystem::solve_root(const std::vector<TreeJoint>& joints,
                            std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                            std::vector<Eigen::Matrix<double, 3, Columns>>& dp) {
  forward<Columns>(root_part(), joints);
  backward<Columns>(root_part(), joints, dv, dp);
}

template <int Columns>
void TreeSystem::factor_solve_root(const std::vector<InverseMass>& inverse_mass,
                                   const std::vector<TreeJoint>& joints,
                                   std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                                   std::vector<Eigen::Matrix<double, 3, Columns>>& dp) {
  inverse_mass_ = inverse_mass.data();
  eliminate<Columns>(root_part(), inverse_mass.data(), joints);
  backward<Columns>(root_part(), joints, dv, dp);
}

template <int Columns>
void TreeSystem::solve_down(int part, const std::vector<TreeJoint>& joints,
                            std::vector<Eigen::Matrix<double, 6, Columns>>& dv,
                            std::vector<Eigen::Matrix<double, 3, Columns>>& dp) {
  backward<Columns>(segment_[part], joints, dv, dp);
}

#define SOFTSTEP_TREE_SOLVE_COLUMNS(C)                                                           \
  template void TreeSystem::solve_up<C>(int, const std::vector<TreeJoint>&, const MoreSides&);   \
  template void TreeSystem::factor_solve_up<C>(int, const std::vector<InverseMass>&,             \
                                               const std::vector<TreeJoint>&, const MoreSides&); \
  template void TreeSystem::factor_solve_root<C>(                                                \
      const std::vector<InverseMass>&, const std::vector<TreeJoint>&,                            \
      std::vector<Eigen::Matrix<double, 6, C>>&, std::vector<Eigen::Matrix<double, 3, C>>&);     \
  template void TreeSystem::solve_root<C>(const std::vector<TreeJoint>&,                         \
                                          std::vector<Eigen::Matrix<double, 6, C>>&,             \
                                          std::vector<Eigen::Matrix<double, 3, C>>&);            \
  template void TreeSystem::solve_down<C>(int, const std::vector<TreeJoint>&,                    \
                                          std::vector<Eigen::Matrix<double, 6, C>>&,             \
                                          std::vector<Eigen::Matrix<double, 3, C>>&);
SOFTSTEP_TREE_SOLVE_COLUMNS(1)
SOFTSTEP_TREE_SOLVE_COLUMNS(2)
SOFTSTEP_TREE_SOLVE_COLUMNS(3)
#undef SOFTSTEP_TREE_SOLVE_COLUMNS

void TreeSystem::solve(const std::vector<TreeJoint>& joints, std::vector<Vec6>& dv,
                       std::vector<Eigen::Vector3d>& dp) {
  dv.resize(body_block_.size());
  dp.resize(joint_inverse_.size());
  solve_up<1>(0, joints, {});
  solve_up<1>(1, joints, {});
  solve_root<1>(joints, dv, dp);
  solve_down<1>(0, joints, dv, dp);
  solve_down<1>(1, joints, dv, dp);
}

void TreeSystem::solve(const std::vector<TreeJoint>& joints,
                       const std::vector<Eigen::Vector3d>& second, std::vector<Vec6x2>& dv,
                       std::vector<Vec3x2>& dp) {
  dv.resize(body_block_.size());
  dp.resize(joint_inverse_.size());
  solve_up<2>(0, joints, {&second});
  solve_up<2>(1, joints, {&second});
  solve_root<2>(joints, dv, dp);
  solve_down<2>(0, joints, dv, dp);
  solve_down<2>(1, joints, dv, dp);
}

}  // namespace softstep::solver
