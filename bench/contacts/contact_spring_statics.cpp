#include "contacts/contact_spring_statics.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

namespace softstep::bench {
namespace {

// One side of a contact point's normal row: where it acts and what it moves.
struct RowSide {
  int column = -1;  // the body's first unknown; -1: the body is held fixed
  Eigen::Vector3d point;             // world
  Eigen::Vector3d arm_cross_normal;  // (point - centre) x normal
  double inv_mass = 0.0;
  Eigen::Matrix3d inv_inertia = Eigen::Matrix3d::Zero();  // world frame
};

// A normal row as the solver sees it: both sides and its effective mass, 1 / (J M^-1 J^T).
struct NormalRow {
  RowSide a, b;
  double effective_mass = 0.0;
};

class RowBuilder {
 public:
  RowBuilder(const World& world, std::span<const BodyId> bodies) : world_(world) {
    for (std::size_t i = 0; i < bodies.size(); ++i) index_[bodies[i].index] = int(i);
  }
  // The body's place in `bodies`, or -1.
  int index(BodyId id) const {
    const auto it = index_.find(id.index);
    return it == index_.end() ? -1 : it->second;
  }
  NormalRow row(const ContactManifold& m, int point) const {
    const ContactPoint& p = m.points[static_cast<std::size_t>(point)];
    NormalRow r{side(m.body_a, p.anchor_a, m.normal), side(m.body_b, p.anchor_b, m.normal)};
    const double inv = r.a.inv_mass + r.b.inv_mass +
                       r.a.arm_cross_normal.dot(r.a.inv_inertia * r.a.arm_cross_normal) +
                       r.b.arm_cross_normal.dot(r.b.inv_inertia * r.b.arm_cross_normal);
    r.effective_mass = 1.0 / inv;
    return r;
  }

 private:
  RowSide side(BodyId id, const Eigen::Vector3d& anchor, const Eigen::Vector3d& n) const {
    const BodyState b = world_.body(id);
    const Eigen::Matrix3d rotation = b.orientation.toRotationMatrix();
    RowSide s;
    const Eigen::Vector3d arm = rotation * anchor;
    s.point = b.position + arm;
    s.arm_cross_normal = arm.cross(n);
    const int i = index(id);
    if (i >= 0) {
      s.column = 6 * i;
      s.inv_mass = 1.0 / b.mass;
      s.inv_inertia = rotation * b.inertia.inverse() * rotation.transpose();
    }
    return s;
  }

  const World& world_;
  std::unordered_map<std::uint32_t, int> index_;
};

double contact_omega(const World& world) {
  return 2.0 * std::numbers::pi * world.settings().contact.hertz;
}

}  // namespace

std::vector<BodyDisplacement> contact_spring_rest(const World& world,
                                                  std::span<const BodyId> bodies,
                                                  std::span<const ContactManifold> contacts) {
  // Unknowns: 6 per body (linear, then angular displacement), in the order of `bodies`.
  const RowBuilder rows(world, bodies);
  const auto dofs = static_cast<Eigen::Index>(6 * bodies.size());
  const double omega = contact_omega(world);
  std::vector<Eigen::Triplet<double>> stiffness;
  double largest_k = 0.0;
  for (const ContactManifold& m : contacts) {
    for (int p = 0; p < m.point_count; ++p) {
      const NormalRow r = rows.row(m, p);
      if (r.a.column < 0 && r.b.column < 0) continue;
      const double k = r.effective_mass * omega * omega;
      largest_k = std::max(largest_k, k);
      // The row's Jacobian: the gap opens by n . (u_b + theta_b x r_b - u_a - theta_a x r_a).
      std::vector<std::pair<int, double>> jacobian;
      const auto add = [&](const RowSide& s, double sign) {
        if (s.column < 0) return;
        for (int c = 0; c < 3; ++c) {
          jacobian.emplace_back(s.column + c, sign * m.normal[c]);
          jacobian.emplace_back(s.column + 3 + c, sign * s.arm_cross_normal[c]);
        }
      };
      add(r.a, -1.0);
      add(r.b, 1.0);
      for (const auto& [i, ji] : jacobian) {
        for (const auto& [j, jj] : jacobian) stiffness.emplace_back(i, j, k * ji * jj);
      }
    }
  }
  // The directions no spring holds: a stiffness 1e-9 of the largest, loaded by nothing.
  for (Eigen::Index i = 0; i < dofs; ++i) stiffness.emplace_back(i, i, 1e-9 * largest_k);
  Eigen::SparseMatrix<double> k_matrix(dofs, dofs);
  k_matrix.setFromTriplets(stiffness.begin(), stiffness.end());

  Eigen::VectorXd load = Eigen::VectorXd::Zero(dofs);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyState b = world.body(bodies[i]);
    load.segment<3>(Eigen::Index(6 * i)) = b.mass * b.gravity_scale * world.settings().gravity;
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k_matrix);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("contact_spring_rest: the spring network cannot be factored");
  }
  const Eigen::VectorXd u = solver.solve(load);
  std::vector<BodyDisplacement> rest(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    rest[i].linear = u.segment<3>(Eigen::Index(6 * i));
    rest[i].angular = u.segment<3>(Eigen::Index(6 * i + 3));
  }
  return rest;
}

double wall_tipping_hertz(const World& world, std::span<const BodyId> bodies,
                          std::span<const ContactManifold> contacts,
                          const Eigen::Vector3d& across) {
  const Eigen::Vector3d up = -world.settings().gravity.normalized();
  const double g = world.settings().gravity.norm();
  // Rows: the distinct heights of the bodies' centres (1 mm apart or more).
  std::vector<double> centre(bodies.size());
  std::map<long long, int> row_of_height;
  double mid_plane = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyState b = world.body(bodies[i]);
    centre[i] = b.position.dot(up);
    row_of_height.emplace(std::llround(centre[i] * 1e3), 0);
    mid_plane += b.position.dot(across) / double(bodies.size());
  }
  int next = 0;
  for (auto& [height, row] : row_of_height) row = next++;
  const auto row_count = static_cast<std::size_t>(next);
  const auto row_of = [&](std::size_t body) {
    return static_cast<std::size_t>(row_of_height.at(std::llround(centre[body] * 1e3)));
  };

  // Per row r: kappa_r / omega^2 of its bottom interface (the points between it and the row
  // below or the ground) and that interface's height (the mean of its points').
  const RowBuilder rows(world, bodies);
  std::vector<double> kappa(row_count, 0.0), base_sum(row_count, 0.0), base_points(row_count, 0.0);
  for (const ContactManifold& m : contacts) {
    const int ia = rows.index(m.body_a), ib = rows.index(m.body_b);
    // The interface belongs to the upper body's row (a body held fixed is below).
    std::size_t upper;
    if (ia < 0 && ib < 0) continue;
    if (ia < 0 || ib < 0) {
      upper = row_of(static_cast<std::size_t>(std::max(ia, ib)));
    } else {
      upper = std::max(row_of(std::size_t(ia)), row_of(std::size_t(ib)));
      if (row_of(std::size_t(ia)) == row_of(std::size_t(ib))) continue;  // side by side
    }
    for (int p = 0; p < m.point_count; ++p) {
      const NormalRow r = rows.row(m, p);
      const Eigen::Vector3d point = 0.5 * (r.a.point + r.b.point);
      const double d = point.dot(across) - mid_plane;
      kappa[upper] += r.effective_mass * d * d;
      base_sum[upper] += point.dot(up);
      base_points[upper] += 1.0;
    }
  }
  std::vector<double> base(row_count), row_mass(row_count, 0.0), lever(row_count, 0.0);
  for (std::size_t r = 0; r < row_count; ++r) {
    if (base_points[r] == 0.0) throw std::invalid_argument("wall_tipping_hertz: a row rests on nothing");
    base[r] = base_sum[r] / base_points[r];
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const double mass = world.body(bodies[i]).mass;
    row_mass[row_of(i)] += mass;
    lever[row_of(i)] += mass * (centre[i] - base[row_of(i)]);
  }
  std::vector<double> weight(row_count, 0.0);  // W_r
  double above = 0.0;
  for (std::size_t r = row_count; r-- > 0;) {
    const double height = r + 1 < row_count ? base[r + 1] - base[r] : 0.0;
    weight[r] = g * (above * height + lever[r]);
    above += row_mass[r];
  }
  // omega^2 K - W is tridiagonal: positive definite iff every pivot of its LDL^T is.
  const auto stands = [&](double omega2) {
    double pivot = 0.0;
    for (std::size_t r = 0; r < row_count; ++r) {
      const double diagonal = omega2 * (kappa[r] + (r + 1 < row_count ? kappa[r + 1] : 0.0)) -
                              weight[r];
      const double off = r > 0 ? omega2 * kappa[r] : 0.0;
      pivot = r > 0 ? diagonal - off * off / pivot : diagonal;
      if (pivot <= 0.0) return false;
    }
    return true;
  };
  double low = 1e-6, high = 1e12;  // omega^2, bisected in the logarithm
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(low * high);
    (stands(mid) ? high : low) = mid;
  }
  return std::sqrt(high) / (2.0 * std::numbers::pi);
}

}  // namespace softstep::bench
